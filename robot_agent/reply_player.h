// How the robot answers: ACK or NACK chords through its loudspeaker (physical layer sink).
//
// The answers themselves are each link's (link::Link::answer_audio). ReplyTimeline writes a file: each chord at the
// audio time of the frame it answers, with silence between, so an offline run leaves a recording aligned with its
// input. LiveReplyPlayer plays on a device from its own thread, so answering never holds up listening; a chord asked
// for while another plays follows it. It first plays a stretch of silence (`warmup`) and only then returns from its
// constructor: a new PulseAudio stream delivers its first sounds late or not at all, and a restarted agent's first ACK
// was lost that way (the seed sender then retransmitted a frame the robot had executed, which the robot, without
// sequence numbers, executed again).
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "physical/audio_io.h"
#include "profile/link_profile.h"

namespace dtmf::agent {

class ReplyPlayer {
 public:
  virtual ~ReplyPlayer() = default;
  // Plays `audio` (a link's answer_audio) as the answer to a frame heard at `audio_ms`.
  virtual void play(std::vector<float> audio, double audio_ms) = 0;
  // The input ended at `audio_ms`: finish what is playing or being written.
  virtual void finish(double audio_ms) = 0;
};

class ReplyTimeline : public ReplyPlayer {
 public:
  ReplyTimeline(const LinkProfile& profile, std::unique_ptr<physical::AudioSink> sink);
  void play(std::vector<float> audio, double audio_ms) override;
  void finish(double audio_ms) override;

 private:
  void silence_until(long long sample);

  const LinkProfile& profile_;
  std::unique_ptr<physical::AudioSink> sink_;
  long long written_ = 0;  // samples written so far
};

class LiveReplyPlayer : public ReplyPlayer {
 public:
  // `realtime`: its thread asks for real-time scheduling (physical/realtime_priority.h).
  LiveReplyPlayer(std::unique_ptr<physical::AudioSink> sink, std::chrono::milliseconds warmup, bool realtime = false);
  ~LiveReplyPlayer() override;
  void play(std::vector<float> audio, double audio_ms) override;
  void finish(double audio_ms) override;

 private:
  void run();

  std::unique_ptr<physical::AudioSink> sink_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::vector<float>> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace dtmf::agent
