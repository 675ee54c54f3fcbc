// Test and benchmark helper: a Teleop client as dtmfctl teleop is one. It opens the
// bidirectional stream with a target, sends each new target at once and repeats the current
// one every 100 ms from its own thread, and keeps every status the server sends (read on a
// second thread) for the caller to wait for and inspect. A gRPC stream takes one Write at a
// time: the caller's and the repeater's take turns (two at once is API misuse, and gRPC
// aborts the process: GRPC_CALL_ERROR_TOO_MANY_OPERATIONS, which crashed dtmf-bench-teleop).
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dtmf/v1/teleop.grpc.pb.h"

namespace dtmf::test_support {

class TeleopClient {
 public:
  TeleopClient(v1::TeleopService::Stub& stub, double linear, double angular, double lease_s,
               const std::string& profile = "fast", const std::string& robot = "")
      : lease_s_(lease_s) {
    stream_ = stub.Teleop(&context_);
    target(linear, angular, profile, robot);
    reader_ = std::thread([this] {
      v1::TeleopResponse r;
      while (stream_->Read(&r)) {
        std::lock_guard lock(mutex_);
        responses_.push_back(r);
        changed_.notify_all();
      }
      std::lock_guard lock(mutex_);
      read_done_ = true;
      changed_.notify_all();
    });
    repeater_ = std::thread([this] {
      std::unique_lock lock(mutex_);
      while (!closing_) {
        changed_.wait_for(lock, std::chrono::milliseconds(100), [this] { return closing_; });
        if (closing_) break;
        const v1::TeleopRequest again = last_;
        lock.unlock();
        const bool ok = write(again);
        lock.lock();
        if (!ok) break;
      }
    });
  }
  ~TeleopClient() {
    if (!finished_) {
      context_.TryCancel();
      finish();
    }
  }

  void target(double linear, double angular, const std::string& profile = "", const std::string& robot = "") {
    v1::TeleopRequest r;
    r.set_linear_mps(linear);
    r.set_angular_radps(angular);
    r.set_lease_s(lease_s_);
    if (!profile.empty()) r.mutable_options()->set_profile(profile);
    if (!robot.empty()) r.mutable_options()->set_robot(robot);
    {
      std::lock_guard lock(mutex_);
      last_ = r;
      last_.clear_options();
    }
    write(r);
  }

  // Waits for a status whose confirmed velocity is (linear, angular), within the payload's steps.
  std::optional<v1::TeleopResponse> confirmed(double linear, double angular, std::chrono::milliseconds within) {
    std::unique_lock lock(mutex_);
    std::optional<v1::TeleopResponse> found;
    changed_.wait_for(lock, within, [&] {
      for (const auto& r : responses_) {
        if (r.confirmed() && std::abs(r.confirmed_linear_mps() - linear) < 0.0002 &&
            std::abs(r.confirmed_angular_radps() - angular) < 0.012)
          found = r;
      }
      return found.has_value() || read_done_;
    });
    return found;
  }

  // Waits for a status carrying a frame event `event`.
  std::optional<v1::TeleopResponse> event(v1::FrameEvent event, std::chrono::milliseconds within) {
    std::unique_lock lock(mutex_);
    std::optional<v1::TeleopResponse> found;
    changed_.wait_for(lock, within, [&] {
      for (const auto& r : responses_) {
        if (r.has_progress() && r.progress().event() == event) found = r;
      }
      return found.has_value() || read_done_;
    });
    return found;
  }

  // Waits until the server ended the stream, repeating the target meanwhile as dtmfctl
  // teleop does (the server's reader sees the end at the next message).
  bool ended(std::chrono::milliseconds within) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, within, [&] { return read_done_; });
  }

  // Ends the stream as a client that is done (half-close), and returns the final status.
  grpc::Status close() {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
      changed_.notify_all();
    }
    repeater_.join();
    {
      std::lock_guard lock(write_mutex_);
      stream_->WritesDone();
    }
    return finish();
  }
  void cancel() { context_.TryCancel(); }
  grpc::Status finish() {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
      changed_.notify_all();
    }
    if (repeater_.joinable()) repeater_.join();
    if (reader_.joinable()) reader_.join();
    finished_ = true;
    return stream_->Finish();
  }
  std::vector<v1::TeleopResponse> responses() {
    std::lock_guard lock(mutex_);
    return responses_;
  }

 private:
  bool write(const v1::TeleopRequest& r) {
    std::lock_guard lock(write_mutex_);
    return stream_->Write(r);
  }

  double lease_s_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<v1::TeleopRequest, v1::TeleopResponse>> stream_;
  std::mutex mutex_;
  std::mutex write_mutex_;  // one Write (or WritesDone) on the stream at a time
  std::condition_variable changed_;
  std::vector<v1::TeleopResponse> responses_;
  v1::TeleopRequest last_;
  bool read_done_ = false;
  bool closing_ = false;
  bool finished_ = false;
  std::thread reader_, repeater_;
};

}  // namespace dtmf::test_support
