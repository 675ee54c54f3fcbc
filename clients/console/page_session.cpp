#include "page_session.h"

#include <nlohmann/json.hpp>

#include "shown_text.h"

namespace dtmf::console {

namespace {

using nlohmann::json;

const char* status_name(grpc::StatusCode code) {
  static constexpr const char* kNames[] = {
      "OK",        "CANCELLED",      "UNKNOWN",           "INVALID_ARGUMENT",   "DEADLINE_EXCEEDED",
      "NOT_FOUND", "ALREADY_EXISTS", "PERMISSION_DENIED", "RESOURCE_EXHAUSTED", "FAILED_PRECONDITION",
      "ABORTED",   "OUT_OF_RANGE",   "UNIMPLEMENTED",     "INTERNAL",           "UNAVAILABLE",
      "DATA_LOSS", "UNAUTHENTICATED"};
  const auto i = static_cast<std::size_t>(code);
  return i < std::size(kNames) ? kNames[i] : "UNKNOWN";
}

// The call's ID in `message` under `key`: a positive integer, or nothing.
std::optional<long long> id_of(const json& message, const char* key) {
  const auto it = message.find(key);
  if (it == message.end() || !it->is_number_integer()) return std::nullopt;
  const long long id = it->get<long long>();
  return id > 0 ? std::optional(id) : std::nullopt;
}

}  // namespace

PageSession::PageSession(ServerLink link, std::string client, std::shared_ptr<PageOutbox> outbox)
    : link_(std::move(link)), client_(std::move(client)), outbox_(std::move(outbox)) {
  put(json{{"hello", {{"server", link_.address}, {"client", client_}}}}.dump(-1, ' ', false,
                                                                             json::error_handler_t::replace),
      false);
}

PageSession::~PageSession() {
  std::map<long long, std::shared_ptr<CallRelay>> calls;
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    calls.swap(calls_);
  }
  for (auto& [id, call] : calls)
    if (call) call->cancel();  // a Teleop stream ends as if its client went: the lease stops it
}

void PageSession::hear(std::string_view text) {
  if (text.size() > kMaxMessageBytes)
    return error("a message of " + std::to_string(text.size()) + " bytes: at most " + std::to_string(kMaxMessageBytes));
  const json message = json::parse(text.begin(), text.end(), nullptr, false);
  if (message.is_discarded() || !message.is_object()) return error("not a JSON object: " + server::shown(text));
  if (const auto id = id_of(message, "open")) {
    const auto method = message.find("method");
    const auto request = message.find("request");
    if (method == message.end() || !method->is_string() || request == message.end() || !request->is_object())
      return error("\"open\" needs \"method\" (a string) and \"request\" (an object)");
    return open(*id, method->get<std::string>(), request->dump());
  }
  for (const char* key : {"send", "close", "cancel"}) {
    const auto id = id_of(message, key);
    if (!id) continue;
    std::shared_ptr<CallRelay> call;
    {
      std::lock_guard lock(mutex_);  // held only to find it: the call's end takes it too
      if (const auto it = calls_.find(*id); it != calls_.end()) call = it->second;
    }
    // Gone: the call ended (its status is on its way). A page's messages are heard one at a
    // time, so its open() has finished before its next message comes.
    if (!call) return;
    if (std::string_view(key) == "close") return call->close();
    if (std::string_view(key) == "cancel") return call->cancel();
    const auto request = message.find("request");
    if (request == message.end() || !request->is_object()) return error("\"send\" needs \"request\" (an object)");
    try {
      const auto parsed = request_from_json(call->method(), request->dump());
      if (!call->send(*parsed)) error("call " + std::to_string(*id) + " takes no more requests now: too many wait");
    } catch (const std::invalid_argument& e) {
      error(e.what());
    }
    return;
  }
  error("a message with none of \"open\", \"send\", \"close\" or \"cancel\" (a positive call ID)");
}

void PageSession::open(long long id, const std::string& method_name, const std::string& request_json) {
  const google::protobuf::MethodDescriptor* method = find_method(method_name);
  if (!method) return error("no method " + server::shown(method_name) + " in dtmf.v1.TeleopService");
  std::unique_ptr<google::protobuf::Message> first;
  try {
    first = request_from_json(*method, request_json);
  } catch (const std::invalid_argument& e) {
    return ended(id, {grpc::StatusCode::INVALID_ARGUMENT, e.what()});
  }
  {
    std::lock_guard lock(mutex_);
    if (closing_) return;
    if (id <= last_id_) return error("call " + std::to_string(id) + ": IDs must grow");
    if (calls_.size() >= kMaxOpenCalls)
      return error("call " + std::to_string(id) + ": " + std::to_string(kMaxOpenCalls) + " calls are open already");
    last_id_ = id;
    calls_[id] = nullptr;  // its place, held while it starts (gRPC may end it before start returns)
  }
  std::weak_ptr<PageSession> session = weak_from_this();
  auto outbox = outbox_;
  CallSink sink{[outbox, id](std::string message, bool droppable) {
                  outbox->put("{\"call\":" + std::to_string(id) + ",\"message\":" + message + "}", droppable);
                },
                [session, id](const grpc::Status& status) {
                  if (auto s = session.lock()) s->ended(id, status);
                }};
  auto call = CallRelay::start(*link_.stub, link_.context(client_), *method, *first, std::move(sink));
  std::lock_guard lock(mutex_);
  const auto place = calls_.find(id);
  if (place != calls_.end()) place->second = std::move(call);  // else it ended already
}

void PageSession::ended(long long id, const grpc::Status& status) {
  {
    std::lock_guard lock(mutex_);
    calls_.erase(id);
  }
  put(json{{"call", id},
           {"status",
            {{"code", static_cast<int>(status.error_code())},
             {"name", status_name(status.error_code())},
             {"message", status.error_message()}}}}
          .dump(-1, ' ', false, json::error_handler_t::replace),
      false);
}

void PageSession::error(const std::string& why) {
  put(json{{"error", why}}.dump(-1, ' ', false, json::error_handler_t::replace), false);
}

void PageSession::put(std::string text, bool droppable) { outbox_->put(std::move(text), droppable); }

}  // namespace dtmf::console
