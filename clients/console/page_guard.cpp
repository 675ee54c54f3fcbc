#include "page_guard.h"

#include <sodium.h>

#include <stdexcept>

#include "shown_text.h"

namespace dtmf::console {

namespace {

constexpr std::size_t kTokenBytes = 32;

bool host_allowed(const std::string& host, const PageGuard& guard) {
  for (const auto& allowed : guard.hosts)
    if (host == allowed) return true;
  return false;
}

// In constant time, so that the time to refuse tells nothing about how much of a guess was right.
bool token_matches(const std::string& presented, const std::string& expected) {
  return !expected.empty() && presented.size() == expected.size() &&
         sodium_memcmp(presented.data(), expected.data(), expected.size()) == 0;
}

}  // namespace

std::vector<std::string> allowed_hosts(const std::string& address, int port) {
  const std::string p = ":" + std::to_string(port);
  std::vector<std::string> hosts{"127.0.0.1" + p, "localhost" + p, "[::1]" + p};
  const bool wildcard = address.empty() || address == "0.0.0.0" || address == "::" || address == "[::]";
  if (!wildcard && address != "127.0.0.1" && address != "localhost" && address != "::1" && address != "[::1]")
    hosts.push_back((address.find(':') != std::string::npos && address.front() != '[' ? "[" + address + "]" : address) +
                    p);
  return hosts;
}

std::optional<Refused> check_request(const RequestHead& head, const PageGuard& guard, std::string_view socket_path) {
  using server::shown;
  if (!host_allowed(head.host, guard))
    return Refused{421, "this console answers to " + guard.hosts.front() + ", not to the host " + shown(head.host) +
                            ": open it by that address (a name that only resolves here is how DNS rebinding "
                            "attacks look)"};
  if (head.method != "GET")
    return Refused{405, "the console takes GET only, not " + shown(head.method) + ": commands go over its socket"};
  if (head.path != socket_path) {
    if (head.upgrade) return Refused{404, "no socket at " + shown(head.path)};
    return std::nullopt;  // the page and its assets: what they are, the server's routes say
  }
  if (!head.upgrade) return Refused{400, "the socket is a WebSocket: open it with the page's script"};
  const std::string own = guard.scheme + "://" + head.host;
  if (head.origin != own)
    return Refused{403, "a socket opened by the page at " + shown(head.origin) + ", not by the console's own (" + own +
                            "): another site may not drive the robots"};
  if (!token_matches(head.token, guard.token))
    return Refused{403, head.token.empty() ? "the socket needs the page's token: reload the page"
                                           : "the token is not this console's (it restarted?): reload the page"};
  return std::nullopt;
}

std::string new_page_token() {
  if (sodium_init() < 0) throw std::runtime_error("libsodium did not start: no random page token can be made");
  unsigned char bytes[kTokenBytes];
  randombytes_buf(bytes, sizeof bytes);
  char hex[2 * kTokenBytes + 1];
  sodium_bin2hex(hex, sizeof hex, bytes, sizeof bytes);
  return hex;
}

}  // namespace dtmf::console
