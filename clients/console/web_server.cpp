#include "web_server.h"

#include <civetweb.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "shown_text.h"

namespace dtmf::console {

namespace {

constexpr const char* kSocketPath = "/socket";
constexpr const char* kTokenMark = "{{PAGE_TOKEN}}";
// The page may load and connect only to this console; nothing may frame it.
constexpr const char* kSecurityHeaders =
    "Content-Security-Policy: default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; "
    "connect-src 'self'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'\r\n"
    "X-Content-Type-Options: nosniff\r\nX-Frame-Options: DENY\r\nReferrer-Policy: no-referrer\r\n"
    "Cross-Origin-Opener-Policy: same-origin\r\nCross-Origin-Resource-Policy: same-origin\r\n";

std::string mime_of(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  return "text/plain; charset=utf-8";  // LICENSE files
}

std::string header(const mg_connection* conn, const char* name) {
  const char* value = mg_get_header(conn, name);
  return value ? value : "";
}

void send(mg_connection* conn, int status, const std::string& mime, const std::string& body, bool cache) {
  mg_printf(conn,
            "HTTP/1.1 %d %s\r\nContent-Type: %s\r\nContent-Length: %zu\r\nCache-Control: %s\r\n%s"
            "Connection: close\r\n\r\n",
            status, mg_get_response_code_text(conn, status), mime.c_str(), body.size(),
            cache ? "max-age=60" : "no-store", kSecurityHeaders);
  mg_write(conn, body.data(), body.size());
}

}  // namespace

std::map<std::string, Asset> load_assets(const std::string& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, Asset> assets;
  if (!fs::is_regular_file(fs::path(dir) / "index.html"))
    throw std::runtime_error("no console page in " + server::shown(dir) +
                             " (index.html): give the folder of the installed page with --assets");
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), dir);
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    const std::string at = relative == "index.html" ? "/" : "/assets/" + relative.generic_string();
    assets[at] = Asset{bytes.str(), mime_of(entry.path())};
  }
  return assets;
}

// One page's socket: its outbox, the thread that writes it to the socket, and its session.
struct WebServer::Page {
  std::shared_ptr<PageOutbox> outbox = std::make_shared<PageOutbox>();
  std::shared_ptr<PageSession> session;
  std::thread writer;
};

extern "C" {
static int request_trampoline(mg_connection* conn) {
  return static_cast<WebServer*>(mg_get_user_data(mg_get_context(conn)))->on_request(conn);
}
static int connect_trampoline(const mg_connection* conn, void* server) {
  return static_cast<WebServer*>(server)->on_socket_connect(conn);
}
static void ready_trampoline(mg_connection* conn, void* server) {
  static_cast<WebServer*>(server)->on_socket_ready(conn);
}
static int data_trampoline(mg_connection* conn, int bits, char* data, size_t length, void* server) {
  return static_cast<WebServer*>(server)->on_socket_data(conn, bits, data, length);
}
static void close_trampoline(const mg_connection* conn, void* server) {
  static_cast<WebServer*>(server)->on_socket_close(conn);
}
}

WebServer::WebServer(
    WebServerOptions options, std::map<std::string, Asset> assets,
    std::function<std::shared_ptr<PageSession>(std::shared_ptr<PageOutbox>, const std::string&)> new_page)
    : options_(std::move(options)), assets_(std::move(assets)), new_page_(std::move(new_page)) {
  const auto index = assets_.find("/");
  if (index == assets_.end()) throw std::runtime_error("the console's assets have no index.html");
  page_html_ = index->second.bytes;
  const auto mark = page_html_.find(kTokenMark);
  if (mark == std::string::npos) throw std::runtime_error("the console's index.html has no place for the page token");
  page_html_.replace(mark, std::string(kTokenMark).size(), options_.token_in_page ? options_.guard.token : "");

  const bool tls = !options_.tls_pem.empty();
  const std::string listen =
      (options_.address.find(':') != std::string::npos ? "[" + options_.address + "]" : options_.address) + ":" +
      std::to_string(options_.port) + (tls ? "s" : "");
  std::vector<const char*> config{"listening_ports",      listen.c_str(), "num_threads",       "24",
                                  "request_timeout_ms",   "10000",        "enable_keep_alive", "no",
                                  "websocket_timeout_ms", "3600000"};
  if (tls) {
    config.push_back("ssl_certificate");
    config.push_back(options_.tls_pem.c_str());
  }
  config.push_back(nullptr);
  mg_callbacks callbacks{};
  callbacks.begin_request = request_trampoline;
  mg_init_library(tls ? MG_FEATURES_TLS : 0);
  context_ = mg_start(&callbacks, this, config.data());
  if (!context_)
    throw std::runtime_error("the console cannot listen on " + listen +
                             ": is the port taken? (choose another with --port, or 0 for any)");
  mg_set_websocket_handler(context_, kSocketPath, connect_trampoline, ready_trampoline, data_trampoline,
                           close_trampoline, this);
  mg_server_port ports[4]{};
  const int n = mg_get_server_ports(context_, 4, ports);
  port_ = n > 0 ? ports[0].port : options_.port;
  options_.guard.scheme = tls ? "https" : "http";
  options_.guard.hosts = allowed_hosts(options_.address, port_);
  for (const auto& host : options_.extra_hosts) options_.guard.hosts.push_back(host);
}

WebServer::~WebServer() {
  if (context_) mg_stop(context_);  // closes every socket: each page's close comes first
}

int WebServer::on_request(mg_connection* conn) {
  const mg_request_info* info = mg_get_request_info(conn);
  RequestHead head;
  head.method = info->request_method ? info->request_method : "";
  head.path = info->local_uri ? info->local_uri : "";
  head.host = header(conn, "Host");
  head.origin = header(conn, "Origin");
  head.upgrade = !header(conn, "Sec-WebSocket-Key").empty();
  if (info->query_string) {
    char token[160] = "";
    if (mg_get_var(info->query_string, std::strlen(info->query_string), "token", token, sizeof token) > 0)
      head.token = token;
  }
  if (const auto refused = check_request(head, options_.guard, kSocketPath)) {
    spdlog::warn("console: refused {} {} from {}: {}", server::shown(head.method), server::shown(head.path),
                 info->remote_addr, refused->why);
    send(conn, refused->http_status, "text/plain; charset=utf-8", refused->why + "\n", false);
    return refused->http_status;
  }
  if (head.path == kSocketPath) {
    if (pages_ < kMaxPages) return 0;  // on to the socket's handlers
    send(conn, 503, "text/plain; charset=utf-8",
         std::to_string(kMaxPages) + " pages are open on this console: close one, then reload\n", false);
    return 503;
  }
  if (head.path == "/") {
    send(conn, 200, "text/html; charset=utf-8", page_html_, false);
    return 200;
  }
  const auto asset = assets_.find(head.path);
  if (asset == assets_.end() || head.path == "/") {
    send(conn, 404, "text/plain; charset=utf-8", "no such page: " + server::shown(head.path) + "\n", false);
    return 404;
  }
  send(conn, 200, asset->second.mime, asset->second.bytes, true);
  return 200;
}

int WebServer::on_socket_connect(const mg_connection*) { return 0; }  // the guard judged it already

void WebServer::on_socket_ready(mg_connection* conn) {
  auto* page = new Page;
  const mg_request_info* info = mg_get_request_info(conn);
  page->session = new_page_(page->outbox, info->remote_addr);
  page->writer = std::thread([conn, outbox = page->outbox] {
    while (const auto text = outbox->take()) {
      if (mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_TEXT, text->data(), text->size()) <= 0) break;
    }
    // A page too slow even for its events is closed: its browser ends the socket, and the
    // page reconnects and says so.
    if (outbox->overflowed()) mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE, "", 0);
    outbox->shut();
  });
  mg_set_user_connection_data(conn, page);
  ++pages_;
}

int WebServer::on_socket_data(mg_connection* conn, int bits, char* data, std::size_t length) {
  auto* page = static_cast<Page*>(mg_get_user_connection_data(conn));
  const int opcode = bits & 0x0f;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  if (opcode == MG_WEBSOCKET_OPCODE_PING || opcode == MG_WEBSOCKET_OPCODE_PONG) return 1;
  // The page sends whole text messages; anything else is not the page's script.
  if (!page || opcode != MG_WEBSOCKET_OPCODE_TEXT || !(bits & 0x80)) return 0;
  page->session->hear(std::string_view(data, length));
  return 1;
}

void WebServer::on_socket_close(const mg_connection* conn) {
  auto* page = static_cast<Page*>(mg_get_user_connection_data(conn));
  if (!page) return;
  page->outbox->shut();
  page->session.reset();  // cancels its calls
  if (page->writer.joinable()) page->writer.join();
  delete page;
  --pages_;
}

}  // namespace dtmf::console
