// The console's HTTP and WebSocket server: civetweb (Debian's libcivetweb-dev), with nothing of
// its own but three routes. Every request's head goes first to the guard (page_guard.h), which
// may refuse it; then
//   GET /           the page, with the page's token written into it (never cached);
//   GET /assets/F   a file of the page (read into memory at start: no path reaches the disk);
//   GET /socket     the page's WebSocket (page_session.h), with one writer thread per page.
// Every answer carries a Content-Security-Policy that lets the page load and connect only to
// this console, and forbids framing; no answer carries an Access-Control header.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "page_guard.h"
#include "page_session.h"

struct mg_context;
struct mg_connection;

namespace dtmf::console {

struct Asset {
  std::string bytes;
  std::string mime;
};

// The page's files in `dir` (index.html and what it loads), by the path they are served at
// ("/", "/assets/console.js"); throws std::runtime_error naming what is missing.
std::map<std::string, Asset> load_assets(const std::string& dir);

struct WebServerOptions {
  std::string address = "127.0.0.1";
  int port = 8080;                       // 0: any free port (port() says which)
  std::string tls_pem;                   // a PEM with the key and the certificate: serve HTTPS
  PageGuard guard;                       // the token; its hosts and scheme are set from where it listens
  std::vector<std::string> extra_hosts;  // other names the page is opened by (host:port)
  bool token_in_page = true;             // false when the operator's own token guards the socket (not on loopback)
};

class WebServer {
 public:
  // Pages open at once: each holds a socket, a writer thread and up to about 6 MB (its outbox,
  // 2 MB, and its calls' waiting requests, 32 × 8 × 16 kB); the 9th socket is refused (503).
  static constexpr std::size_t kMaxPages = 8;

  // Starts serving; throws std::runtime_error naming what failed (the port taken, say).
  WebServer(WebServerOptions options, std::map<std::string, Asset> assets,
            std::function<std::shared_ptr<PageSession>(std::shared_ptr<PageOutbox>, const std::string& peer)> new_page);
  ~WebServer();
  int port() const { return port_; }
  std::size_t pages() const { return pages_; }

  // civetweb's callbacks, public for its C trampolines only.
  int on_request(mg_connection* conn);
  int on_socket_connect(const mg_connection* conn);
  void on_socket_ready(mg_connection* conn);
  int on_socket_data(mg_connection* conn, int bits, char* data, std::size_t length);
  void on_socket_close(const mg_connection* conn);

 private:
  struct Page;
  WebServerOptions options_;
  std::map<std::string, Asset> assets_;
  std::string page_html_;  // index.html with the token
  std::function<std::shared_ptr<PageSession>(std::shared_ptr<PageOutbox>, const std::string&)> new_page_;
  mg_context* context_ = nullptr;
  int port_ = 0;
  std::atomic<std::size_t> pages_{0};
};

}  // namespace dtmf::console
