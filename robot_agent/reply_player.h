// How the robot answers: ACK or NACK chords through its loudspeaker (physical layer sink).
//
// ReplyTimeline writes a file: each chord at the audio time of the frame it answers, with
// silence between, so an offline run leaves a recording aligned with its input.
// LiveReplyPlayer plays on a device from its own thread, so answering never holds up
// listening; a chord asked for while another plays follows it.
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "physical/audio_io.h"
#include "profile/link_profile.h"
#include "signal/tone_plan.h"

namespace dtmf::agent {

class ReplyPlayer {
 public:
  virtual ~ReplyPlayer() = default;
  virtual void play(signal::Reply reply, double audio_ms) = 0;
  // The input ended at `audio_ms`: finish what is playing or being written.
  virtual void finish(double audio_ms) = 0;
};

class ReplyTimeline : public ReplyPlayer {
 public:
  ReplyTimeline(const LinkProfile& profile, std::unique_ptr<physical::AudioSink> sink);
  void play(signal::Reply reply, double audio_ms) override;
  void finish(double audio_ms) override;

 private:
  void silence_until(long long sample);

  const LinkProfile& profile_;
  std::unique_ptr<physical::AudioSink> sink_;
  long long written_ = 0;  // samples written so far
};

class LiveReplyPlayer : public ReplyPlayer {
 public:
  LiveReplyPlayer(const LinkProfile& profile, std::unique_ptr<physical::AudioSink> sink);
  ~LiveReplyPlayer() override;
  void play(signal::Reply reply, double audio_ms) override;
  void finish(double audio_ms) override;

 private:
  void run();

  const LinkProfile& profile_;
  std::unique_ptr<physical::AudioSink> sink_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<signal::Reply> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace dtmf::agent
