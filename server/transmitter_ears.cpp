// Transmitter: the sender's ears. listen() reads the microphone on a thread of its own, feeds
// every block's level to the carrier sense and every answer heard to a queue; wait_reply()
// takes from that queue the answer to the frame on air, until its deadline.
#include <spdlog/spdlog.h>

#include "link/answer_wait.h"
#include "transmitter.h"

namespace dtmf::server {

namespace {
// Another's robot is taken to answer under our exchanges once it has been read so twice within
// this: two senders in step read each other's robot's answers every exchange (about every
// 200 ms), while one answer of our own robots misread as naming another (the fleet teleop
// bench, three robots: once in 120 s) made the sender defer for 1.7 s and every lease lapse.
constexpr double kMaskedAgainMs = 5000;
}  // namespace

// Decodes at normal priority: a device is drained by a thread of its own
// (physical/capture_thread.h), which only copies.
void Transmitter::listen() {
  ReplyListeners& listener = *ears_;
  std::vector<float> block(static_cast<std::size_t>(listener.block_samples()));
  double audio_ms = 0;
  while (true) {
    {
      std::lock_guard lock(mutex_);
      if (stopping_) return;
    }
    std::size_t got = 0;
    try {
      got = microphone_->read(block);
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      unavailable_ = std::string("the microphone failed: ") + e.what();
      spdlog::error("{}", unavailable_);
      changed_.notify_all();
      return;
    }
    if (got == 0) return;  // the input ended (a file, or a stopped simulated air)
    audio_ms += 1000.0 * static_cast<double>(got) / profile_.sample_rate_hz;
    const double now = now_ms();
    mic_offset_ms_ = now - audio_ms;
    const std::span<const float> heard_block(block.data(), got);
    const double level_dbfs = reliability::block_level_dbfs(heard_block);
    bool busy = false;
    double floor_dbfs = 0;
    {
      std::lock_guard lock(mutex_);
      const bool waiting = carrier_.own_on();
      carrier_.hear(level_dbfs, now);
      busy = carrier_.busy_now();
      floor_dbfs = carrier_.floor_dbfs();
      if (busy)
        spdlog::debug("the air at {:.0f} ms: {:.1f} dBFS over a floor of {:.1f}: another's sound{}", now, level_dbfs,
                      floor_dbfs, waiting ? " (while our exchange goes on: counted if not our answer)" : "");
    }
    publish_levels(heard_block, audio_ms, busy, level_dbfs, floor_dbfs);
    for (const HeardAnswer& heard : listener.feed(heard_block)) {
      publish_heard(heard, heard.answer.heard_ms, level_dbfs);
      std::lock_guard lock(mutex_);
      // The block just read ends now; the reply was heard a little earlier.
      const double heard_at_ms = now - (audio_ms - heard.answer.heard_ms);
      replies_.push_back({heard, heard_at_ms});
      // Another's answer ends its exchange (reliability/air_access.h). Not a tag chord's
      // reading: the tag listener reads one out of noise or music up to every hop (talk-off,
      // benchmarks.md), where an ACK or a NACK is heard a hundred times an hour at most.
      if (!heard.answer.tag_reading) carrier_.answer_read(heard_at_ms);
      changed_.notify_all();
    }
  }
}

bool Transmitter::another_robots(const link::Link& link, const link::Answer& answer) const {
  // A tag chord names no robot, and the seed's answers name none either.
  if (answer.tag_reading || !link.addresses_robots()) return false;
  for (const Robot& r : robots_)
    for (const link::Link* l : r.links)
      if (l->addresses_robots() && l->options().address == answer.address) return false;
  return true;
}

std::optional<Transmitter::HeardReply> Transmitter::wait_reply(const link::Link& link, const link::TransmitFrame& frame,
                                                               double since_ms, double until_ms) {
  std::unique_lock lock(mutex_);
  link::AnswerWait wait(link, frame);
  while (true) {
    while (!replies_.empty()) {
      const HeardReply reply = replies_.front();
      replies_.pop_front();
      if (reply.steady_ms < since_ms || reply.answer.link != &link) continue;  // not an answer to this frame
      if (another_robots(link, reply.answer.answer)) {
        // Read under our exchange, where the microphone takes every sound for ours: another's
        // exchange went on under it unheard (reliability/carrier_sense.h, answer_masked).
        const unsigned address = reply.answer.answer.address;
        const bool again =
            masked_once_ && masked_once_->first == address && reply.steady_ms - masked_once_->second <= kMaskedAgainMs;
        masked_once_ = std::pair{address, reply.steady_ms};
        if (again) carrier_.answer_masked(reply.steady_ms);
        spdlog::debug("an answer from robot {}, none of ours, while frame {} waits: {}", address,
                      frame.sequence.value_or(0),
                      again ? "another sender shares the air" : "once so far (a misread of ours?)");
        continue;
      }
      if (!wait.answered_by(reply.answer.answer)) {
        if (reply.answer.answer.tag_reading) continue;  // a tag chord spelling another tag
        spdlog::debug("an ACK naming frame {} while frame {} waits: late, ignored",
                      reply.answer.answer.sequence.value_or(0), frame.sequence.value_or(0));
        continue;
      }
      return reply;
    }
    if (stopping_ || stop_waiting_ || now_ms() >= until_ms) return std::nullopt;  // a Stop overtakes the wait
    changed_.wait_for(lock, std::chrono::duration<double, std::milli>(std::min(until_ms - now_ms(), 50.0)));
  }
}

}  // namespace dtmf::server
