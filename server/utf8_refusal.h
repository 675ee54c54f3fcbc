// Turns protobuf's refusal of a request whose string field is not UTF-8 into
// INVALID_ARGUMENT naming the field.
//
// proto3 strings must be UTF-8, and protobuf refuses to parse a message that breaks this
// before any handler runs; gRPC then answers INTERNAL with an empty message, which tells a
// caller neither that it was their fault nor which field. Protobuf does name the field, in a
// log line written on the thread that parsed the request: a log handler keeps that name per
// thread, and a server interceptor, which runs on the same thread right after the parse
// (POST_RECV_MESSAGE with no message), rewrites the status before it is sent.
#pragma once

#include <grpcpp/support/server_interceptor.h>

#include <memory>

namespace dtmf::server {

// Installs the protobuf log handler (once per process; other protobuf log lines still go
// to stderr) and returns the interceptor factory for ServerBuilder::experimental().
std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> utf8_refusal_interceptor();

}  // namespace dtmf::server
