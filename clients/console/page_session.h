// One page's socket: what the page asks and what it is sent. The page opens calls of the
// public API (call_relay.h) and follows them:
//   page → console  {"open":ID,"method":"Drive","request":{...}}   a call, with its first request
//                   {"send":ID,"request":{...}}                    a stream's next request (Teleop)
//                   {"close":ID}                                   no more requests
//                   {"cancel":ID}                                  end the call now
//   console → page  {"hello":{"server":...,"client":...}}          once, on connecting
//                   {"call":ID,"message":{...}}                    each message the server sends
//                   {"call":ID,"status":{"code":N,"name":...,"message":...}}   the call's end, once
//                   {"error":"..."}                                a message the console could not take
//                   {"dropped_columns":N}                          columns lost because the page read slowly
// Everything goes out through the page's outbox (page_outbox.h), which one writer drains.
// A message from the page is bounded (16 kB), its IDs are positive and new, and at most 32
// calls are open at once; what breaks a rule is answered with an error naming it, quoted.
#pragma once

#include <grpcpp/generic/generic_stub.h>

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "call_relay.h"
#include "page_outbox.h"

namespace dtmf::console {

// How the console reaches the server: a stub and a context per call (the server's token in it,
// and the page's name, which the server shows when it refuses another page its robot).
struct ServerLink {
  std::shared_ptr<grpc::GenericStub> stub;
  std::function<std::unique_ptr<grpc::ClientContext>(const std::string& client)> context;
  std::string address;  // shown to the page
};

class PageSession : public std::enable_shared_from_this<PageSession> {
 public:
  static constexpr std::size_t kMaxMessageBytes = 16 * 1024;  // a request is under 1 kB
  static constexpr std::size_t kMaxOpenCalls = 32;

  // `client` names the page to the server ("console page 3, 127.0.0.1"). Held by a
  // shared_ptr: its calls' ends find it through a weak one.
  PageSession(ServerLink link, std::string client, std::shared_ptr<PageOutbox> outbox);
  ~PageSession();  // cancels every call still open

  void hear(std::string_view text);  // a text message from the page

 private:
  void open(long long id, const std::string& method_name, const std::string& request_json);
  void error(const std::string& why);
  void ended(long long id, const grpc::Status& status);
  void put(std::string text, bool droppable);

  ServerLink link_;
  const std::string client_;
  std::shared_ptr<PageOutbox> outbox_;
  std::mutex mutex_;
  std::map<long long, std::shared_ptr<CallRelay>> calls_;
  long long last_id_ = 0;
  bool closing_ = false;
};

}  // namespace dtmf::console
