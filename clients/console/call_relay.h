// One call of dtmf.v1.TeleopService made for a page. The page names the method and sends its
// requests in proto3's JSON mapping (as grpcurl and buf curl do); each goes to the server as
// the method's message, and each message the server sends comes back as JSON, then the call's
// status. Every method (unary, server stream, the Teleop bidi stream) travels as one generic
// bidi call, so the page can do exactly what any gRPC client can, no more, and every request
// is checked by the server's own rules: the console adds no RPC and no rule of its own.
// A small reactor in the manner of gRPC's callback clients: no thread, no sleep.
#pragma once

#include <google/protobuf/message.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace dtmf::console {

// Where a call's results go: each message as JSON, then the status, once. `droppable`: a
// spectrum column, which a page that reads too slowly may lose (its events it may not).
struct CallSink {
  std::function<void(std::string json, bool droppable)> message;
  std::function<void(const grpc::Status& status)> ended;
};

// The method of dtmf.v1.TeleopService called `name` ("Drive", "WatchAir"), if there is one.
const google::protobuf::MethodDescriptor* find_method(const std::string& name);

// A request of `method` read from `json`; throws std::invalid_argument naming what is wrong.
std::unique_ptr<google::protobuf::Message> request_from_json(const google::protobuf::MethodDescriptor& method,
                                                             const std::string& json);

class CallRelay final : public grpc::ClientBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer> {
 public:
  // At most this many requests wait to be written (a Teleop page sends a target a key press,
  // and each is written in well under a millisecond on loopback).
  static constexpr std::size_t kMaxPendingRequests = 8;

  // Starts the call with its first request; `sink` hears of it until ended. The relay owns
  // itself until then; `context` carries the server's token, if it needs one.
  static std::shared_ptr<CallRelay> start(grpc::GenericStub& stub, std::unique_ptr<grpc::ClientContext> context,
                                          const google::protobuf::MethodDescriptor& method,
                                          const google::protobuf::Message& first, CallSink sink);

  // Another request (a Teleop stream's next target); false if too many wait or the call ended.
  bool send(const google::protobuf::Message& request);
  // No more requests: the server sees the stream's end (the page ended a Teleop stream).
  void close();
  // Ends the call now (the page went away): the server sees it cancelled.
  void cancel();
  const google::protobuf::MethodDescriptor& method() const { return method_; }

  void OnWriteDone(bool ok) override;
  void OnReadDone(bool ok) override;
  void OnDone(const grpc::Status& status) override;

 private:
  CallRelay(std::unique_ptr<grpc::ClientContext> context, const google::protobuf::MethodDescriptor& method,
            CallSink sink);
  void write_next();  // under mutex_

  std::unique_ptr<grpc::ClientContext> context_;
  const google::protobuf::MethodDescriptor& method_;
  CallSink sink_;
  std::shared_ptr<CallRelay> self_;  // until OnDone
  std::unique_ptr<google::protobuf::Message> reply_;
  grpc::ByteBuffer read_buffer_;

  // Recursive: a write's completion may come back on the thread that started it, within it.
  std::recursive_mutex mutex_;
  std::deque<grpc::ByteBuffer> pending_;
  grpc::ByteBuffer writing_buffer_;
  bool writing_ = false;
  bool closing_ = false;      // half-close once the pending are written
  bool half_closed_ = false;  // ... and done so
  bool done_ = false;
};

}  // namespace dtmf::console
