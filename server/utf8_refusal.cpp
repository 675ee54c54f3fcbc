#include "utf8_refusal.h"

#include <google/protobuf/stubs/logging.h>

#include <cstdio>
#include <mutex>
#include <string>

namespace dtmf::server {

namespace {

// The field protobuf last refused on this thread, e.g. "dtmf.v1.StartRunRequest.label".
thread_local std::string t_refused_field;

google::protobuf::LogHandler* g_previous_handler = nullptr;

void on_protobuf_log(google::protobuf::LogLevel level, const char* filename, int line, const std::string& message) {
  // protobuf: "String field 'dtmf.v1.StartRunRequest.label' contains invalid UTF-8 data ..."
  static const std::string kPrefix = "String field '";
  if (message.find("invalid UTF-8") != std::string::npos && message.rfind(kPrefix, 0) == 0) {
    const auto end = message.find('\'', kPrefix.size());
    if (end != std::string::npos) t_refused_field = message.substr(kPrefix.size(), end - kPrefix.size());
  }
  if (g_previous_handler) g_previous_handler(level, filename, line, message);
}

class Utf8Refusal final : public grpc::experimental::Interceptor {
 public:
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    using grpc::experimental::InterceptionHookPoints;
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_MESSAGE)) {
      // No message: the request did not parse, and a refused field says why.
      if (methods->GetRecvMessage() == nullptr && !t_refused_field.empty()) refused_field_ = t_refused_field;
      t_refused_field.clear();
    }
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS) && !refused_field_.empty() &&
        methods->GetSendStatus().error_code() == grpc::StatusCode::INTERNAL) {
      // "dtmf.v1.StartRunRequest.label" -> "label", as every other INVALID_ARGUMENT names it.
      const auto dot = refused_field_.rfind('.');
      const std::string field = dot == std::string::npos ? refused_field_ : refused_field_.substr(dot + 1);
      methods->ModifySendStatus({grpc::StatusCode::INVALID_ARGUMENT,
                                 field + ": not valid UTF-8 (" + refused_field_ + "); send text as UTF-8"});
    }
    methods->Proceed();
  }

 private:
  std::string refused_field_;
};

class Utf8RefusalFactory final : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateServerInterceptor(grpc::experimental::ServerRpcInfo*) override {
    return new Utf8Refusal;
  }
};

}  // namespace

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> utf8_refusal_interceptor() {
  static std::once_flag installed;
  std::call_once(installed, [] { g_previous_handler = google::protobuf::SetLogHandler(&on_protobuf_log); });
  return std::make_unique<Utf8RefusalFactory>();
}

}  // namespace dtmf::server
