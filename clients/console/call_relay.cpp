#include "call_relay.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/json_util.h>

#include <stdexcept>

#include "dtmf/v1/teleop.grpc.pb.h"
#include "shown_text.h"

namespace dtmf::console {

namespace {

grpc::ByteBuffer to_buffer(const google::protobuf::Message& message) {
  const std::string bytes = message.SerializeAsString();
  grpc::Slice slice(bytes);
  return grpc::ByteBuffer(&slice, 1);
}

bool from_buffer(const grpc::ByteBuffer& buffer, google::protobuf::Message& message) {
  std::vector<grpc::Slice> slices;
  if (!buffer.Dump(&slices).ok()) return false;
  std::string bytes;
  for (const auto& s : slices) bytes.append(reinterpret_cast<const char*>(s.begin()), s.size());
  return message.ParseFromString(bytes);
}

std::unique_ptr<google::protobuf::Message> new_message(const google::protobuf::Descriptor& type) {
  const google::protobuf::Message* prototype =
      google::protobuf::MessageFactory::generated_factory()->GetPrototype(&type);
  return std::unique_ptr<google::protobuf::Message>(prototype->New());
}

// A spectrum column of WatchAir: the one kind of message a slow page may lose.
bool is_droppable(const google::protobuf::Message& message) {
  const auto* spectrum = message.GetDescriptor()->FindFieldByName("spectrum");
  return message.GetDescriptor() == v1::WatchAirResponse::descriptor() && spectrum &&
         message.GetReflection()->HasField(message, spectrum);
}

}  // namespace

const google::protobuf::MethodDescriptor* find_method(const std::string& name) {
  // teleop.proto's descriptor, registered when its messages are linked in (as they are here).
  (void)v1::WatchAirResponse::descriptor();
  const auto* service = google::protobuf::DescriptorPool::generated_pool()->FindServiceByName("dtmf.v1.TeleopService");
  return service ? service->FindMethodByName(name) : nullptr;
}

std::unique_ptr<google::protobuf::Message> request_from_json(const google::protobuf::MethodDescriptor& method,
                                                             const std::string& json) {
  auto request = new_message(*method.input_type());
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;  // a misspelt field is an error, not a default
  const auto status = google::protobuf::util::JsonStringToMessage(json, request.get(), options);
  if (!status.ok())
    throw std::invalid_argument("the " + method.name() + " request is not a " + method.input_type()->name() + ": " +
                                server::shown(std::string(status.message())));
  return request;
}

CallRelay::CallRelay(std::unique_ptr<grpc::ClientContext> context, const google::protobuf::MethodDescriptor& method,
                     CallSink sink)
    : context_(std::move(context)),
      method_(method),
      sink_(std::move(sink)),
      reply_(new_message(*method.output_type())) {}

std::shared_ptr<CallRelay> CallRelay::start(grpc::GenericStub& stub, std::unique_ptr<grpc::ClientContext> context,
                                            const google::protobuf::MethodDescriptor& method,
                                            const google::protobuf::Message& first, CallSink sink) {
  auto relay = std::shared_ptr<CallRelay>(new CallRelay(std::move(context), method, std::move(sink)));
  relay->self_ = relay;
  const std::string path = "/" + method.service()->full_name() + "/" + method.name();
  stub.PrepareBidiStreamingCall(relay->context_.get(), path, grpc::StubOptions(), relay.get());
  {
    std::lock_guard lock(relay->mutex_);
    relay->pending_.push_back(to_buffer(first));
    // One request is all a method that does not stream its requests takes.
    relay->closing_ = !method.client_streaming();
    relay->write_next();
  }
  relay->StartRead(&relay->read_buffer_);
  relay->StartCall();
  return relay;
}

bool CallRelay::send(const google::protobuf::Message& request) {
  std::lock_guard lock(mutex_);
  if (done_ || closing_ || pending_.size() >= kMaxPendingRequests) return false;
  pending_.push_back(to_buffer(request));
  write_next();
  return true;
}

void CallRelay::close() {
  std::lock_guard lock(mutex_);
  closing_ = true;
  write_next();
}

void CallRelay::cancel() { context_->TryCancel(); }

void CallRelay::write_next() {
  if (writing_ || done_ || half_closed_) return;
  if (pending_.empty()) {
    if (closing_) {
      half_closed_ = true;
      StartWritesDone();
    }
    return;
  }
  writing_buffer_ = std::move(pending_.front());
  pending_.pop_front();
  writing_ = true;
  if (pending_.empty() && closing_) {
    half_closed_ = true;  // the last request carries the half-close
    StartWriteLast(&writing_buffer_, grpc::WriteOptions());
  } else {
    StartWrite(&writing_buffer_);
  }
}

void CallRelay::OnWriteDone(bool ok) {
  std::lock_guard lock(mutex_);
  writing_ = false;
  if (!ok) return;  // the call is over; OnDone says how
  write_next();
}

void CallRelay::OnReadDone(bool ok) {
  if (!ok) return;  // the server's stream ended; OnDone has its status
  reply_->Clear();
  if (from_buffer(read_buffer_, *reply_)) {
    google::protobuf::util::JsonPrintOptions options;
    options.preserve_proto_field_names = true;  // the page reads the names of teleop.proto
    options.always_print_primitive_fields = true;
    std::string json;
    if (google::protobuf::util::MessageToJsonString(*reply_, &json, options).ok())
      sink_.message(std::move(json), is_droppable(*reply_));
  }
  StartRead(&read_buffer_);
}

void CallRelay::OnDone(const grpc::Status& status) {
  {
    std::lock_guard lock(mutex_);
    done_ = true;
    pending_.clear();
  }
  sink_.ended(status);
  self_.reset();
}

}  // namespace dtmf::console
