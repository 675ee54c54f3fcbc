// The files dtmf-server reads its transport security from: the TLS certificate (public), the
// TLS private key and the bearer token (secrets).
//
// A secret file that its group or others may read or write (mode & 077) is refused before a
// byte of it is read, with the chmod that fixes it, as the link key is (security/link_key.h).
// An empty or blank token file is refused: a server that took it would ask no caller for a
// token at all. No error text carries a byte of any of the files.
//
// A file that decides what the server trusts, public but not to be changed by others (the
// robots file: which key each robot gets), is checked on the open file too: not a symbolic
// link (opened with O_NOFOLLOW), a regular file, this user's or root's (root may change any
// file anyway, and a packaged /etc file is root's while a dynamic user reads it), and no
// group or others may write it. Each refusal says what is wrong and the chmod, chown or path
// that fixes it.
#pragma once

#include <stdexcept>
#include <string>

#include "bearer_token_auth.h"

namespace dtmf::server {

class SecretFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The text of a file only its owner may read or write, without trailing spaces, CRs and
// newlines; `what` names it in errors ("auth token", "TLS key"). Throws SecretFileError.
std::string read_secret_file(const std::string& path, const char* what);

// The text of a public file (the TLS certificate), trimmed the same way; throws SecretFileError.
std::string read_public_file(const std::string& path, const char* what);

// A file whose writer decides what the server trusts.
struct TrustedFile {
  const char* what;     // names it in errors: "robots" (the robots file 'PATH')
  const char* flag;     // the flag that names it, for the fix: "--robots"
  const char* decides;  // what its writer decides: "which key each robot gets"
};

// The text of such a file, trimmed the same way, if only its owner, this user or root, may
// change it and `path` is not a symbolic link; throws SecretFileError with the fix.
std::string read_trusted_file(const std::string& path, const TrustedFile& kind);

// The bearer token in `path` (dtmf-server --auth-token-file): a secret file that holds more
// than white space. Throws SecretFileError saying what is wrong and how to make a good one.
std::string read_token_file(const std::string& path);

// The transport security of the server's flags (an empty path: not given). Does not judge
// the combination: server_credentials() does.
ServerSecurity read_security_files(const std::string& tls_cert, const std::string& tls_key,
                                   const std::string& auth_token_file);

}  // namespace dtmf::server
