#include "link/link.h"

#include <stdexcept>

#include "link/fast_link.h"
#include "link/seed_link.h"
#include "signal/fft_wisdom.h"

namespace dtmf::link {

std::string_view event_name(ReceptionEvent event) {
  switch (event) {
    case ReceptionEvent::Broken:
      return "";
    case ReceptionEvent::Reset:
      return "reset";
    case ReceptionEvent::ModeSelected:
      return "mode_selected";
    case ReceptionEvent::Command:
      return "command";
    case ReceptionEvent::Ignored:
      return "ignored";
    case ReceptionEvent::Repeat:
      return "repeat";
    case ReceptionEvent::Synchronised:
      return "sync";
    case ReceptionEvent::Refused:
      return "refused";
    case ReceptionEvent::Renewed:
      return "renewal";
  }
  return "";
}

std::string_view reason_name(RefusalReason reason) {
  switch (reason) {
    case RefusalReason::None:
      return "";
    case RefusalReason::Authentication:
      return "authentication";
    case RefusalReason::Payload:
      return "payload";
  }
  return "";
}

Link::Link(const LinkProfile& profile, LinkOptions options) : profile_(profile), options_(std::move(options)) {
  if (options_.address > 7)
    throw std::invalid_argument("a robot's address is 0..7, not " + std::to_string(options_.address));
  if (options_.key && !options_.counters) options_.counters = std::make_shared<security::MemoryCounterStore>();
  if (options_.room_key && !options_.room_counters)
    options_.room_counters = std::make_shared<security::MemoryCounterStore>();
}

std::optional<TransmitFrame> Link::plan_payload_word(std::uint32_t) const { return std::nullopt; }

void Link::confirmed(const TransmitFrame&) {}

std::vector<float> Link::render(std::span<const TransmitFrame> frames) const {
  std::vector<float> audio(static_cast<std::size_t>(profile_.samples_for_ms(frame_start_ms(frames.size()))), 0.0f);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto start = static_cast<std::size_t>(profile_.samples_for_ms(frame_start_ms(i)));
    if (audio.size() < start + frames[i].audio.size()) audio.resize(start + frames[i].audio.size(), 0.0f);
    for (std::size_t k = 0; k < frames[i].audio.size(); ++k) audio[start + k] += frames[i].audio[k];
  }
  return audio;
}

std::unique_ptr<Link> make_link(const LinkProfile& profile, LinkOptions options) {
  if (std::holds_alternative<HopPlan>(profile.plan)) return std::make_unique<FastLink>(profile, std::move(options));
  return std::make_unique<SeedLink>(profile, std::move(options));
}

std::vector<std::unique_ptr<Link>> make_links(const LinkOptions& options,
                                              const std::vector<const LinkProfile*>& profiles) {
  std::vector<std::unique_ptr<Link>> links;
  for (const LinkProfile* p : profiles) links.push_back(make_link(*p, options));
  return links;
}

const LinkProfile& default_profile(std::span<const std::unique_ptr<Link>> links) {
  if (links.empty()) throw std::invalid_argument("a sender needs at least one link");
  for (const auto& l : links) {
    if (l->keyed() && l->can_authenticate()) return l->profile();
  }
  return links.front()->profile();
}

std::string plan_cache_default_file() { return signal::fft_wisdom_default_file(); }

void use_plan_cache(const std::string& path) { signal::use_fft_wisdom_file(path); }

}  // namespace dtmf::link
