// Turns protobuf's refusal of a request whose string field is not UTF-8 into
// INVALID_ARGUMENT naming the field.
//
// proto3 strings must be UTF-8, and protobuf refuses to parse a message that breaks this
// before any handler runs; gRPC then answers INTERNAL (UNIMPLEMENTED for a callback method)
// with an empty message, which tells a caller neither that it was their fault nor which field. A server interceptor,
// which runs on the parsing thread right after the parse (POST_RECV_MESSAGE with no message), rewrites that status to
// INVALID_ARGUMENT before it is sent.
//
// Which field: protobuf (before 22) names it in a log line on that thread. A log handler
// keeps the full name of any string field of this API the line mentions, checked against
// the generated descriptors, so the line's wording does not matter. At start a probe
// parses a label that is not UTF-8 and records whether the name came back
// (utf8_refusal_names_fields(); tests/server/server_text_test.cpp pins it, so an upgrade
// that loses the name fails there). Without a name, the refusal still says what to fix.
#pragma once

#include <grpcpp/support/server_interceptor.h>

#include <memory>

namespace dtmf::server {

// Installs the protobuf log handler (once per process; other protobuf log lines still go
// to stderr) and returns the interceptor factory for ServerBuilder::experimental().
std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> utf8_refusal_interceptor();

// Whether this protobuf names the string field it refuses (the start-up probe's result).
bool utf8_refusal_names_fields();

}  // namespace dtmf::server
