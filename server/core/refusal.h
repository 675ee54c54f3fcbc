// Why the sender did not take a command: a value, carried up to the gRPC boundary, where each
// kind is one status code (teleop_service.cpp: status_of). Refusals are the sender's answer to
// its callers' input, not failures of its own, so they are returned, never thrown.
#pragma once

#include <string>

namespace dtmf::server {

struct Refusal {
  enum class Kind {
    QueueFull,        // the queue is full: retry later, or send Stop (which goes first)
    Unavailable,      // the sender is stopping, or its audio failed
    Unrecorded,       // its record cannot be written (an API call that answers OK is stored)
    RoomKeyMissing,   // a stop for every robot, with keyed robots and no room key
    Unauthenticated,  // a profile without a MAC from a sender with a key
    Unsendable,       // the profile's frames cannot carry the command (`why` names the profile)
    NoProfile,        // no profile that can send it
  };
  Refusal(Kind k, std::string reason) : kind(k), why(std::move(reason)) {}
  Kind kind;
  std::string why;  // what was wrong and what to do
};

}  // namespace dtmf::server
