// Drive, Turn, Stop, Reset and RunTestSequence as gRPC server streams: one small reactor
// follows a command's job (the test sequence's jobs one after another) and writes each of its
// progress events as it comes. No thread and no poll: the job's events, a write done and the
// client's cancel are its inputs (reactor_steps.h), and its step does what they call for. A
// client that cancels or stops reading cancels the command (a chord on air completes; queued
// frames are withdrawn); the stream ends with the command's outcome (outcome_status).
#pragma once

#include <grpcpp/grpcpp.h>

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <variant>

#include "job.h"
#include "reactor_steps.h"
#include "refusal.h"

namespace dtmf::server {

// How a command's outcome ends its RPC.
grpc::Status outcome_status(Job& job);
// The status that answers a refusal of the sender's (teleop_service.cpp).
grpc::Status status_of(const Refusal& refusal);

template <class Response>
class CommandReactor final : public grpc::ServerWriteReactor<Response> {
 public:
  // What to follow next, after `last` (nullptr at first), which ended well: a job, or the
  // status the call ends with (OK once all are done). Called by the step, which holds no lock
  // of the sender's, so it may submit.
  using Next = std::function<std::variant<std::shared_ptr<Job>, grpc::Status>(const Job* last)>;
  // The response for one event of `job`.
  using Fill = std::function<void(Response&, Job& job, const ProgressEvent&)>;

  // Called once, as the call ends, whichever way.
  using Ended = std::function<void()>;

  // Starts following; gRPC owns the returned reactor until OnDone.
  static CommandReactor* start(Next next, Fill fill, Ended ended = {}) {
    auto reactor =
        std::shared_ptr<CommandReactor>(new CommandReactor(std::move(next), std::move(fill), std::move(ended)));
    CommandReactor* r = reactor.get();
    r->self_ = reactor;
    r->steps_.emplace(std::weak_ptr<void>(reactor), [r] { r->step(); });
    r->steps_->run();
    return r;
  }

  void OnWriteDone(bool ok) override {
    {
      std::lock_guard lock(mutex_);
      writing_ = false;
      if (!ok) client_gone_ = true;
    }
    steps_->run();
  }
  void OnCancel() override {
    {
      std::lock_guard lock(mutex_);
      client_gone_ = true;
    }
    steps_->run();
  }
  void OnDone() override { self_.reset(); }  // the last owner but a job's step about to run

 private:
  CommandReactor(Next next, Fill fill, Ended ended)
      : next_(std::move(next)), fill_(std::move(fill)), ended_(std::move(ended)) {}

  // One step: the next job, its next event written, or the call's end. Only steps_ runs it.
  void step() {
    while (!finished_) {
      bool gone = false;
      {
        std::lock_guard lock(mutex_);
        if (writing_) return;  // OnWriteDone steps again
        gone = client_gone_;
      }
      if (!job_ && !take_next()) return;
      if (gone && !cancelled_) {
        cancelled_ = true;  // queued frames are withdrawn; a chord on air completes
        job_->cancel();
      }
      if (std::optional<ProgressEvent> event = job_->take_event()) {
        if (gone) continue;
        response_.Clear();
        fill_(response_, *job_, *event);
        {
          std::lock_guard lock(mutex_);
          writing_ = true;
        }
        this->StartWrite(&response_);
        return;
      }
      if (!job_->finished_and_drained()) return;  // its next event steps again
      job_->on_event(nullptr);
      last_ = std::exchange(job_, nullptr);
      if (gone || !outcome_status(*last_).ok()) return finish(outcome_status(*last_));
    }
  }

  // The next job to follow; false when the call ended instead.
  bool take_next() {
    auto next = next_(last_.get());
    if (auto* status = std::get_if<grpc::Status>(&next)) {
      finish(*status);
      return false;
    }
    job_ = std::get<std::shared_ptr<Job>>(std::move(next));
    std::weak_ptr<CommandReactor> told = self_;
    // The job's events come under the transmitter's locks: the step runs on gRPC's threads.
    job_->on_event([told] {
      if (auto r = told.lock()) r->steps_->run_soon();
    });
    return true;
  }

  void finish(const grpc::Status& status) {
    finished_ = true;
    if (ended_) ended_();
    this->Finish(status);
  }

  Next next_;
  Fill fill_;
  Ended ended_;
  std::shared_ptr<CommandReactor> self_;  // held until OnDone
  std::optional<ReactorSteps> steps_;
  // The step's own.
  std::shared_ptr<Job> job_;
  std::shared_ptr<Job> last_;
  bool cancelled_ = false;
  bool finished_ = false;
  Response response_;
  // The reactions'.
  std::mutex mutex_;
  bool writing_ = false;
  bool client_gone_ = false;
};

}  // namespace dtmf::server
