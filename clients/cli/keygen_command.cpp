// dtmfctl keygen FILE: a new link key (security/link_key.h), written with mode 0600. The
// same file goes to the sender (dtmf-server --key) and to its robots (dtmf-agent --key),
// over a channel an eavesdropper cannot read (docs/security.md, "Pairing").
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "offline_commands.h"
#include "security/link_key.h"

namespace dtmf::cli {

void add_keygen_command(CLI::App& app, Action& run, const GlobalOptions& global) {
  auto file = std::make_shared<std::string>();
  CLI::App* keygen = app.add_subcommand(
      "keygen", "Write a new random link key with its key id to FILE (mode 0600); never overwrites a file");
  keygen->add_option("file", *file, "where to write the key")->required();
  keygen->callback([file, &run, &global] {
    run = [file, &global] {
      const auto key = security::LinkKey::generate();
      key->save(*file);
      if (global.json) {
        std::printf("%s\n", nlohmann::json{{"key_id", key->id_hex()}, {"file", *file}}.dump().c_str());
        return 0;
      }
      std::printf(
          "wrote key %s to %s (mode 0600)\n"
          "give the same file to the sender (dtmf-server --key) and to the robot (dtmf-agent --key) over a channel\n"
          "no one else can read: scp, or a USB stick you keep (docs/security.md, \"Pairing\")\n",
          key->id_hex().c_str(), file->c_str());
      return 0;
    };
  });
}

}  // namespace dtmf::cli
