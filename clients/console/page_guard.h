// Who may load the console's page and drive through it. The console is a web page on this
// machine, and any other site open in the same browser can send it requests: a cross-site
// form, a WebSocket opened from evil.example (WebSockets obey no same-origin rule), or a
// name of the attacker's that resolves to 127.0.0.1 a second after the page loaded (DNS
// rebinding: the browser then takes the attacker's page for the console's origin).
//
// So every request is judged on its head alone, before anything else reads it:
//   - Host must name the console as the user reached it: its port on a loopback name
//     (127.0.0.1, localhost, [::1]) or on a name the operator gave. A rebinding name fails.
//   - Only GET. Nothing the console does is reached by a form or a fetch: commands come only
//     over the socket.
//   - The socket also needs an Origin that is the console's own (scheme and allowed host),
//     and the page's token: 32 random bytes, new at every start, written only into the
//     page, which another site cannot read (no CORS header is ever sent).
// Pure: no I/O; the server (web_server.h) hands it the head and sends what it says.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dtmf::console {

// What the console answers to.
struct PageGuard {
  std::string scheme = "http";     // "https" with TLS
  std::vector<std::string> hosts;  // "127.0.0.1:8080", "localhost:8080", ... as a Host header names them
  std::string token;               // the page's token (hex)
};

// The hosts a console listening on `address`:`port` answers to: the loopback names with the
// port, and `address` itself when it is a name or address other than a wildcard.
std::vector<std::string> allowed_hosts(const std::string& address, int port);

// A request's head, as the HTTP server read it (absent headers empty).
struct RequestHead {
  std::string method;
  std::string path;      // without the query
  std::string host;      // Host
  std::string origin;    // Origin
  std::string token;     // the socket's token (its query's token=...)
  bool upgrade = false;  // a WebSocket handshake
};

// Why a request is refused, with the HTTP status to answer.
struct Refused {
  int http_status;
  std::string why;  // safe to show: names nothing the request sent beyond a bounded, quoted echo
};

// Whether `head` may go on; the refusal otherwise. The socket path is `socket_path`.
std::optional<Refused> check_request(const RequestHead& head, const PageGuard& guard,
                                     std::string_view socket_path = "/socket");

// 32 random bytes as 64 hex digits (libsodium's randombytes).
std::string new_page_token();

}  // namespace dtmf::console
