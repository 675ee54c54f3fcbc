// The console's guard: who may load its page and open its socket (clients/console/page_guard.h).
// Each refusal is the answer to an attack a site open in the same browser can make.
#include "page_guard.h"

#include <gtest/gtest.h>

using namespace dtmf::console;

namespace {

PageGuard guard() {
  PageGuard g;
  g.hosts = allowed_hosts("127.0.0.1", 8080);
  g.token = std::string(64, 'a');
  return g;
}

RequestHead socket_request() {
  RequestHead h;
  h.method = "GET";
  h.path = "/socket";
  h.host = "127.0.0.1:8080";
  h.origin = "http://127.0.0.1:8080";
  h.token = std::string(64, 'a');
  h.upgrade = true;
  return h;
}

}  // namespace

TEST(PageGuard, AnswersToTheLoopbackNamesWithItsPortAndToTheAddressItServes) {
  EXPECT_EQ(allowed_hosts("127.0.0.1", 8080),
            (std::vector<std::string>{"127.0.0.1:8080", "localhost:8080", "[::1]:8080"}));
  EXPECT_EQ(allowed_hosts("0.0.0.0", 80).size(), 3u) << "a wildcard names no host: --allowed-host does";
  EXPECT_EQ(allowed_hosts("console.lab", 443).back(), "console.lab:443");
  EXPECT_EQ(allowed_hosts("fd00::5", 8443).back(), "[fd00::5]:8443");
}

TEST(PageGuard, ThePageAndItsAssetsNeedOnlyTheRightHost) {
  RequestHead page{"GET", "/", "localhost:8080", "", "", false};
  EXPECT_FALSE(check_request(page, guard()));
  page.path = "/assets/js/console.js";
  EXPECT_FALSE(check_request(page, guard()));
}

TEST(PageGuard, ADnsRebindingHostIsRefusedBeforeAnythingElse) {
  // evil.example resolved to 127.0.0.1 after its page loaded: the browser sends its own name.
  for (const char* host : {"evil.example:8080", "127.0.0.1", "127.0.0.1:8081", "", "127.0.0.1.nip.io:8080",
                           "localhost:8080.evil.example"}) {
    RequestHead page{"GET", "/", host, "", "", false};
    const auto refused = check_request(page, guard());
    ASSERT_TRUE(refused) << host;
    EXPECT_EQ(refused->http_status, 421) << host;
    EXPECT_NE(refused->why.find("127.0.0.1:8080"), std::string::npos) << "it says how to open it: " << refused->why;
  }
}

TEST(PageGuard, OnlyGetIsTaken) {
  for (const char* method : {"POST", "PUT", "DELETE", "OPTIONS", "PATCH"}) {
    RequestHead post{method, "/", "127.0.0.1:8080", "http://evil.example", "", false};
    const auto refused = check_request(post, guard());
    ASSERT_TRUE(refused) << method;
    EXPECT_EQ(refused->http_status, 405);
  }
}

TEST(PageGuard, TheSocketNeedsTheConsolesOwnOriginAndThePagesToken) {
  EXPECT_FALSE(check_request(socket_request(), guard()));

  for (const char* origin : {"http://evil.example", "null", "", "https://127.0.0.1:8080", "http://localhost:8080",
                             "http://127.0.0.1:8080.evil.example"}) {
    RequestHead h = socket_request();
    h.origin = origin;  // another site's page opened it (WebSockets obey no same-origin rule)
    const auto refused = check_request(h, guard());
    ASSERT_TRUE(refused) << origin;
    EXPECT_EQ(refused->http_status, 403) << origin;
  }
  RequestHead no_token = socket_request();
  no_token.token.clear();
  ASSERT_TRUE(check_request(no_token, guard()));
  EXPECT_NE(check_request(no_token, guard())->why.find("needs the page's token"), std::string::npos);
  RequestHead wrong = socket_request();
  wrong.token[63] = 'b';
  ASSERT_TRUE(check_request(wrong, guard()));
  EXPECT_EQ(check_request(wrong, guard())->http_status, 403);
  RequestHead longer = socket_request();
  longer.token += "a";
  EXPECT_TRUE(check_request(longer, guard()));
  RequestHead plain = socket_request();
  plain.upgrade = false;
  ASSERT_TRUE(check_request(plain, guard()));
  EXPECT_EQ(check_request(plain, guard())->http_status, 400);
}

TEST(PageGuard, AGuardWithoutATokenOpensNoSocket) {
  PageGuard g = guard();
  g.token.clear();
  RequestHead h = socket_request();
  h.token.clear();
  EXPECT_TRUE(check_request(h, g)) << "an empty token must not match an empty token";
}

TEST(PageGuard, WhatARequestSentIsEchoedQuotedAndBounded) {
  RequestHead h{"GET", "/", "evil\r\nSet-Cookie: x=1\x1b[2J" + std::string(300, 'h'), "", "", false};
  const auto refused = check_request(h, guard());
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->why.find('\n'), std::string::npos) << refused->why;
  EXPECT_EQ(refused->why.find('\x1b'), std::string::npos) << refused->why;
  EXPECT_NE(refused->why.find("\\r\\n"), std::string::npos) << refused->why;
  EXPECT_LT(refused->why.size(), 400u) << refused->why;
}

TEST(PageGuard, EachStartHasANewTokenOf32RandomBytes) {
  const std::string a = new_page_token();
  const std::string b = new_page_token();
  EXPECT_EQ(a.size(), 64u);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_NE(a, b);
}
