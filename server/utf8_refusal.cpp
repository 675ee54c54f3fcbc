#include "utf8_refusal.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/stubs/common.h>

#include <mutex>
#include <regex>
#include <string>

#include "dtmf/v1/teleop.pb.h"

// Protobuf 22 moved its logging to Abseil and dropped SetLogHandler; there the field cannot
// be learnt from the log, and refusals fall back to a message naming no field.
#if GOOGLE_PROTOBUF_VERSION < 4022000 && __has_include(<google/protobuf/stubs/logging.h>)
#include <google/protobuf/stubs/logging.h>
#define DTMF_PROTOBUF_LOG_HANDLER 1
#else
#define DTMF_PROTOBUF_LOG_HANDLER 0
#endif

namespace dtmf::server {

namespace {

// The string field protobuf last refused on this thread, e.g. "dtmf.v1.StartRunRequest.label".
thread_local std::string t_refused_field;
bool g_names_fields = false;

// The full name of a string field of this API that a log line names, whatever the line's
// wording: a name the generated descriptors know as a string field, or "".
std::string string_field_named_in(const std::string& message) {
  static const std::regex kFullName(R"(dtmf\.v1\.[A-Za-z_][A-Za-z0-9_.]*)");
  for (std::sregex_iterator it(message.begin(), message.end(), kFullName), end; it != end; ++it) {
    const auto* field = google::protobuf::DescriptorPool::generated_pool()->FindFieldByName(it->str());
    if (field && field->type() == google::protobuf::FieldDescriptor::TYPE_STRING) return it->str();
  }
  return {};
}

#if DTMF_PROTOBUF_LOG_HANDLER
google::protobuf::LogHandler* g_previous_handler = nullptr;

void on_protobuf_log(google::protobuf::LogLevel level, const char* filename, int line, const std::string& message) {
  if (auto field = string_field_named_in(message); !field.empty()) t_refused_field = std::move(field);
  if (g_previous_handler) g_previous_handler(level, filename, line, message);
}
#endif

// Whether this protobuf still names the field it refuses: a label that is not UTF-8 must
// fail to parse and leave its field's name behind on this thread.
bool probe_names_fields() {
  v1::StartRunRequest request;
  request.set_label("x");
  std::string bytes = request.SerializeAsString();
  bytes.back() = '\xff';
  t_refused_field.clear();
  const bool parsed = v1::StartRunRequest().ParseFromString(bytes);
  const bool named = !parsed && t_refused_field == "dtmf.v1.StartRunRequest.label";
  t_refused_field.clear();
  return named;
}

class Utf8Refusal final : public grpc::experimental::Interceptor {
 public:
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    using grpc::experimental::InterceptionHookPoints;
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_MESSAGE)) {
      // No message: the request did not parse; a refused field, if protobuf named one, says why.
      if (methods->GetRecvMessage() == nullptr) {
        unparsed_ = true;
        refused_field_ = t_refused_field;
      }
      t_refused_field.clear();
    }
    // A synchronous method answers an unparsed request INTERNAL, a callback method (the
    // streams that follow the air) UNIMPLEMENTED; both with no message.
    const auto unparsed_status = [&] {
      const grpc::StatusCode code = methods->GetSendStatus().error_code();
      return code == grpc::StatusCode::INTERNAL || code == grpc::StatusCode::UNIMPLEMENTED;
    };
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS) && unparsed_ &&
        unparsed_status()) {
      methods->ModifySendStatus({grpc::StatusCode::INVALID_ARGUMENT, refusal_text()});
    }
    methods->Proceed();
  }

 private:
  std::string refusal_text() const {
    if (refused_field_.empty()) {
      return "the request could not be parsed: a string field that is not valid UTF-8, or bytes that are not this "
             "method's request message; send text as UTF-8 and the message this method takes";
    }
    // "dtmf.v1.StartRunRequest.label" -> "label", as every other INVALID_ARGUMENT names it.
    const auto dot = refused_field_.rfind('.');
    const std::string field = dot == std::string::npos ? refused_field_ : refused_field_.substr(dot + 1);
    return field + ": not valid UTF-8 (" + refused_field_ + "); send text as UTF-8";
  }

  bool unparsed_ = false;
  std::string refused_field_;
};

class Utf8RefusalFactory final : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateServerInterceptor(grpc::experimental::ServerRpcInfo*) override {
    return new Utf8Refusal;
  }
};

void install() {
  static std::once_flag installed;
  std::call_once(installed, [] {
#if DTMF_PROTOBUF_LOG_HANDLER
    g_previous_handler = google::protobuf::SetLogHandler(&on_protobuf_log);
#endif
    g_names_fields = probe_names_fields();
  });
}

}  // namespace

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> utf8_refusal_interceptor() {
  install();
  return std::make_unique<Utf8RefusalFactory>();
}

bool utf8_refusal_names_fields() {
  install();
  return g_names_fields;
}

}  // namespace dtmf::server
