// Test helper: a fresh database in the test cluster (DTMF_DB_URL, started by the ctest
// fixture `pg`), dropped again at the end of the test.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <pqxx/pqxx>
#include <stdexcept>
#include <string>

#include "database.h"

namespace dtmf::test_support {

inline std::string cluster_url() {
  const char* url = std::getenv("DTMF_DB_URL");
  return url ? url : "";
}

class TempDatabase {
 public:
  TempDatabase() {
    static int counter = 0;
    name_ = "dtmf_test_" + std::to_string(::getpid()) + "_" + std::to_string(++counter);
    pqxx::connection admin(cluster_url());
    pqxx::nontransaction tx(admin);
    tx.exec("DROP DATABASE IF EXISTS " + name_);
    tx.exec("CREATE DATABASE " + name_);
    const std::string base = cluster_url();
    url_ = base.substr(0, base.rfind('/') + 1) + name_;
  }
  ~TempDatabase() {
    try {
      pqxx::connection admin(cluster_url());
      pqxx::nontransaction tx(admin);
      tx.exec("DROP DATABASE IF EXISTS " + name_ + " WITH (FORCE)");
    } catch (...) {
    }
  }
  const std::string& url() const { return url_; }

  // The first column of the first row of `sql`, as T (committed, in its own transaction).
  template <class T>
  T query(const std::string& sql) const {
    pqxx::connection c(url_);
    pqxx::work tx(c);
    const pqxx::result result = tx.exec(sql);
    if (result.empty()) throw std::runtime_error("no rows from: " + sql);
    const T value = result[0][0].as<T>();
    tx.commit();
    return value;
  }

 private:
  std::string name_;
  std::string url_;
};

}  // namespace dtmf::test_support
