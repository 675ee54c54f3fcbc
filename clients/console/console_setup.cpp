#include "console_setup.h"

#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "bearer_token_auth.h"
#include "secret_file.h"
#include "server_connection.h"

namespace dtmf::console {

namespace {

constexpr const char* kConnection = "The server (as dtmfctl's)";
constexpr const char* kServing = "Serving the page";

// civetweb takes the key and the certificate from one PEM file: written for it, readable by
// this user only, and removed once the server has read it.
class JoinedPem {
 public:
  JoinedPem(const std::string& key, const std::string& cert) {
    char name[] = "/tmp/dtmf-console-tls-XXXXXX";
    const int fd = ::mkstemp(name);  // mode 0600
    if (fd < 0) throw std::runtime_error("cannot write the TLS key for the web server: no temporary file");
    ::close(fd);
    path_ = name;
    std::ofstream(path_) << key << "\n" << cert << "\n";
  }
  ~JoinedPem() { std::filesystem::remove(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string page_name(std::size_t page, const std::string& peer) {
  return "dtmf-console page " + std::to_string(page) + " (" + peer + ")";
}

}  // namespace

void add_console_flags(CLI::App& app, ConsoleFlags& flags, const std::string& program) {
  app.add_option("--server", flags.server.address, "dtmf-server address host:port")
      ->envname("DTMF_SERVER")
      ->capture_default_str()
      ->group(kConnection);
  app.add_option("--tls-ca", flags.server.tls_ca, "connect with TLS, trusting this PEM certificate")
      ->envname("DTMF_CONSOLE_TLS_CA")
      ->group(kConnection);
  app.add_option("--token-file", flags.server.token_file, "the server's bearer token (dtmf-server --auth-token-file)")
      ->envname("DTMF_CONSOLE_TOKEN_FILE")
      ->group(kConnection);
  app.add_option("--address", flags.address, "where to serve the page: loopback unless HTTPS and a token guard it")
      ->envname("DTMF_CONSOLE_ADDRESS")
      ->capture_default_str()
      ->group(kServing);
  app.add_option("--port", flags.port, "the page's port (0: any free one)")
      ->envname("DTMF_CONSOLE_PORT")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str()
      ->group(kServing);
  app.add_option("--tls-cert", flags.tls_cert, "PEM certificate: serve HTTPS (with --tls-key)")
      ->envname("DTMF_CONSOLE_TLS_CERT")
      ->group(kServing);
  app.add_option("--tls-key", flags.tls_key, "PEM private key")->envname("DTMF_CONSOLE_TLS_KEY")->group(kServing);
  app.add_option("--auth-token-file", flags.auth_token_file,
                 "the operator's token, asked by the page (needed off loopback, with HTTPS)")
      ->envname("DTMF_CONSOLE_AUTH_TOKEN_FILE")
      ->group(kServing);
  app.add_option("--allowed-host", flags.allowed_hosts,
                 "another name the page is opened by (host:port, as the browser's address bar has it)")
      ->envname("DTMF_CONSOLE_ALLOWED_HOSTS")
      ->delimiter(',')
      ->group(kServing);
  app.add_flag("--allow-anyone-on-the-network", flags.allow_anyone,
               "serve off loopback without HTTPS and a token: anyone who reaches the port drives the robots")
      ->envname("DTMF_CONSOLE_ALLOW_ANYONE_ON_THE_NETWORK")
      ->group(kServing);
  // Where this binary is (not argv[0], which a PATH search leaves without its folder).
  std::error_code error;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) self = std::filesystem::absolute(program, error);
  flags.assets = (self.parent_path() / ".." / "share" / "dtmf-teleop" / "console").lexically_normal().string();
  app.add_option("--assets", flags.assets, "the page's files")
      ->envname("DTMF_CONSOLE_ASSETS")
      ->capture_default_str()
      ->group(kServing);
}

std::unique_ptr<Console> start_console(const ConsoleFlags& flags) {
  if (flags.tls_cert.empty() != flags.tls_key.empty())
    throw std::invalid_argument("HTTPS needs both --tls-cert and --tls-key");
  const bool tls = !flags.tls_cert.empty();
  const bool loopback = server::is_loopback_address(flags.address);
  const bool guarded = tls && !flags.auth_token_file.empty();
  if (!loopback && !guarded && !flags.allow_anyone)
    throw std::invalid_argument(
        "serving the console on " + flags.address + " without HTTPS and a token would let anyone who reaches port " +
        std::to_string(flags.port) +
        " drive the robots: add --tls-cert, --tls-key and --auth-token-file, serve this machine only (--address "
        "127.0.0.1, the default), or accept the risk with --allow-anyone-on-the-network");
  if (!flags.auth_token_file.empty() && !tls && !loopback)
    throw std::invalid_argument(
        "--auth-token-file without HTTPS would send the token in clear text: add --tls-cert "
        "and --tls-key");
  if (!loopback && !guarded)
    spdlog::warn("the console on {} is open to anyone who reaches port {}: they can drive the robots", flags.address,
                 flags.port);

  WebServerOptions web;
  web.address = flags.address;
  web.port = flags.port;
  web.extra_hosts = flags.allowed_hosts;
  // The operator's token where one is given; otherwise a new one each start, in the page.
  web.token_in_page = flags.auth_token_file.empty();
  web.guard.token = web.token_in_page ? new_page_token() : server::read_token_file(flags.auth_token_file);
  std::optional<JoinedPem> pem;
  if (tls) {
    pem.emplace(server::read_secret_file(flags.tls_key, "TLS key"),
                server::read_public_file(flags.tls_cert, "TLS certificate"));
    web.tls_pem = pem->path();
  }

  const cli::ServerChannel channel = cli::open_server_channel(flags.server);
  ServerLink link;
  link.stub = std::make_shared<grpc::GenericStub>(channel.channel);
  link.address = flags.server.address;
  link.context = [token = channel.token](const std::string& client) {
    auto context = std::make_unique<grpc::ClientContext>();
    if (!token.empty()) context->AddMetadata("authorization", "Bearer " + token);
    context->AddMetadata("x-dtmf-client", client);
    return context;
  };
  auto pages = std::make_shared<std::atomic<std::size_t>>(0);
  auto console = std::make_unique<Console>();
  console->web = std::make_unique<WebServer>(
      std::move(web), load_assets(flags.assets),
      [link, pages](std::shared_ptr<PageOutbox> outbox, const std::string& peer) {
        return std::make_shared<PageSession>(link, page_name(++*pages, peer), std::move(outbox));
      });
  const std::string host = loopback && flags.address != "::1"             ? "127.0.0.1"
                           : flags.address.find(':') != std::string::npos ? "[" + flags.address + "]"
                                                                          : flags.address;
  console->url = std::string(tls ? "https" : "http") + "://" + host + ":" + std::to_string(console->web->port()) + "/";
  return console;
}

}  // namespace dtmf::console
