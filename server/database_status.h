// The status of an RPC that reads the database (reports, receptions) when it cannot.
#pragma once

#include <grpcpp/grpcpp.h>

#include <exception>
#include <string>

namespace dtmf::server {

inline grpc::Status no_database() {
  return {grpc::StatusCode::FAILED_PRECONDITION,
          "this server runs without a database (--db none): there are no runs, reports or receptions; start it "
          "with --db URL"};
}

inline grpc::Status database_trouble(const std::exception& e) {
  return {grpc::StatusCode::UNAVAILABLE, std::string("the database cannot answer: ") + e.what()};
}

}  // namespace dtmf::server
