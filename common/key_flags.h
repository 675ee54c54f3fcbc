// What dtmf-server, dtmf-agent and dtmfctl share about keys: the flags (--key, --state-dir,
// and the robot's --new-key) and the link options they make — the key read from its file
// (security/link_key.h), the freshness counters kept in the state directory
// (security/counter_file.h), opened and locked at start. The key's bytes never leave the
// LinkKey: flags name files, logs name the key id.
// Header-only: each program includes it once.
#pragma once

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <string>

#include "link/link.h"
#include "security/counter_file.h"
#include "security/link_key.h"
#include "user_dirs.h"

namespace dtmf::program {

struct KeyFlags {
  std::string key_file;       // empty: no key
  std::string state_dir;      // where the counters live
  bool new_key = false;       // the robot's --new-key: the key was just made, it has no state yet
  std::string room_key_file;  // empty: no room key (docs/security.md, "The room key")
};

// A user's own state directory: $XDG_STATE_HOME/dtmf-teleop, else ~/.local/state/dtmf-teleop.
inline std::string default_user_state_dir() { return user_state_dir().value_or(".dtmf-teleop-state"); }

// --key FILE and --state-dir DIR, with their environment variables (PREFIX_KEY_FILE,
// PREFIX_STATE_DIR) and the state directory's default.
inline void add_key_flags(CLI::App& app, KeyFlags& flags, const std::string& env_prefix,
                          const std::string& default_state_dir) {
  flags.state_dir = default_state_dir;
  app.add_option("--key", flags.key_file,
                 "the link key this side shares with the other (dtmfctl keygen FILE): authenticated frames and answers")
      ->envname(env_prefix + "_KEY_FILE");
  app.add_option("--state-dir", flags.state_dir, "where the freshness counters of the key are kept (with --key)")
      ->envname(env_prefix + "_STATE_DIR")
      ->capture_default_str();
}

// The robot's --new-key (PREFIX_NEW_KEY): once, for the first start with a key just made.
inline void add_new_key_flag(CLI::App& app, KeyFlags& flags, const std::string& env_prefix) {
  app.add_flag("--new-key", flags.new_key,
               "with --key: the key was just made (dtmfctl keygen): write its counter state, then run. Once, at "
               "pairing: refused when the key has state here; without it, a key with no state here is refused")
      ->envname(env_prefix + "_NEW_KEY")
      ->needs(app.get_option("--key"));
}

// --room-key FILE (PREFIX_ROOM_KEY_FILE): the key every robot and sender of a room holds for the
// stop every robot obeys (dtmfctl stop --all).
inline void add_room_key_flag(CLI::App& app, KeyFlags& flags, const std::string& env_prefix) {
  app.add_option("--room-key", flags.room_key_file,
                 "the room key every robot and sender of the room holds (dtmfctl keygen FILE): it authenticates the "
                 "stop for every robot (dtmfctl stop --all); its counters are kept in --state-dir")
      ->envname(env_prefix + "_ROOM_KEY_FILE");
}

// Warns when the counter found on disk for `what` lies ahead of this machine's clock by more
// than `slack` counters: a clock that ran fast wrote it, or this clock is behind; `then` says
// what follows (docs/security.md, "Counters ahead of the clock").
inline void warn_future_counter(const security::FileCounterStore& store, const std::string& what, std::uint64_t slack,
                                const std::string& then) {
  const auto stored = store.stored_counter();
  const auto now = std::chrono::system_clock::now();
  if (!stored || *stored <= security::clock_counter_floor(now) + slack) return;
  spdlog::warn(
      "{}: the counter kept in {} ({}) lies {:.0f} s ahead of this machine's clock: a clock that ran fast "
      "wrote it, or this clock is behind (set it: timedatectl, NTP). {}",
      what, store.directory().string(), *stored, security::seconds_ahead_of_clock(*stored, now), then);
}

// The sender's link for the stop every robot obeys: with --room-key, keyed with the room key,
// its counters following the clock (security/room_freshness.h); without, plain.
inline link::LinkOptions room_link_options(const KeyFlags& flags) {
  link::LinkOptions options;
  if (flags.room_key_file.empty()) return options;
  options.key = security::LinkKey::load(flags.room_key_file);
  const auto counters = security::FileCounterStore::open_sender(
      flags.state_dir, *options.key, std::chrono::system_clock::now, security::CounterPace::Clock);
  options.counters = counters;
  warn_future_counter(*counters, "room key " + options.key->id_hex(), security::kSenderBlock,
                      "Robots take room counters up to " + std::to_string(security::kClockMarginS) +
                          " s ahead of their clocks; past that a stop still stops them, its counter not kept");
  spdlog::info("room key {} from {}: stops for every robot go authenticated", options.key->id_hex(),
               flags.room_key_file);
  return options;
}

// The sender's link options the flags give (dtmf-server, dtmfctl encode): nothing but the
// address without a key; with one, its counters, locked for this process from now on.
inline link::LinkOptions link_options(const KeyFlags& flags, std::uint8_t address = 0) {
  link::LinkOptions options;
  options.address = address;
  if (flags.key_file.empty()) return options;
  options.key = security::LinkKey::load(flags.key_file);
  const auto counters = security::FileCounterStore::open_sender(flags.state_dir, *options.key);
  options.counters = counters;
  warn_future_counter(*counters, "key " + options.key->id_hex(), security::kSenderBlock,
                      "The robot refuses counters more than " + std::to_string(security::kClockMarginS) +
                          " s ahead of its clock (a Stop still stops it)");
  spdlog::info("key {} from {}; counters in {}", options.key->id_hex(), flags.key_file, flags.state_dir);
  return options;
}

// The robot's (dtmf-agent): with a key, its accepted counter read (or, with --new-key,
// written) and locked before this returns, so before the robot listens. Throws when there is
// no state for the key and no --new-key, or the state is damaged.
inline link::LinkOptions robot_link_options(const KeyFlags& flags, std::uint8_t address) {
  link::LinkOptions options;
  options.address = address;
  if (!flags.room_key_file.empty()) {
    options.room_key = security::LinkKey::load(flags.room_key_file);
    const auto room_counters =
        security::FileCounterStore::open_robot(flags.state_dir, *options.room_key, security::RobotKey::Room);
    options.room_counters = room_counters;
    warn_future_counter(*room_counters, "room key " + options.room_key->id_hex(), security::kClockMargin,
                        "The room's window re-anchors to this clock at the next stop for every robot, so true "
                        "stops are taken again (security/room_freshness.h)");
    spdlog::info("room key {} from {}: a stop for every robot is taken only under it (newest room counter {})",
                 options.room_key->id_hex(), flags.room_key_file, options.room_counters->last_accepted());
  }
  if (flags.key_file.empty()) return options;
  options.key = security::LinkKey::load(flags.key_file);
  const auto counters = security::FileCounterStore::open_robot(
      flags.state_dir, *options.key, flags.new_key ? security::RobotKey::New : security::RobotKey::Paired);
  options.counters = counters;
  warn_future_counter(*counters, "key " + options.key->id_hex(), security::kSenderBlock,
                      "Frames are refused until the sender's counters pass it, or, past " +
                          std::to_string(security::kClockMarginS) +
                          " s, until this clock does (a Stop still stops the robot); if the clocks are right, make "
                          "a new key (dtmfctl keygen) and pair both sides again");
  if (flags.new_key) {
    spdlog::info(
        "key {} from {}: new, its counter state written in {} (accepted 0); start without --new-key from now on",
        options.key->id_hex(), flags.key_file, flags.state_dir);
  } else {
    spdlog::info("key {} from {}; counters in {} (last accepted {})", options.key->id_hex(), flags.key_file,
                 flags.state_dir, counters->last_accepted());
  }
  return options;
}

}  // namespace dtmf::program
