#include "link/link.h"

#include <stdexcept>

#include "link/fast_link.h"
#include "link/seed_link.h"

namespace dtmf::link {

std::size_t Link::frame_count(const command::Command& command) const {
  std::uint8_t scratch_sequence = 0;
  return plan(command, scratch_sequence).size();
}

std::optional<TransmitFrame> Link::plan_word(std::uint32_t) const { return std::nullopt; }

std::vector<float> Link::render(std::span<const TransmitFrame> frames) const {
  std::vector<float> audio(static_cast<std::size_t>(profile_.samples_for_ms(frame_start_ms(frames.size()))), 0.0f);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto start = static_cast<std::size_t>(profile_.samples_for_ms(frame_start_ms(i)));
    if (audio.size() < start + frames[i].audio.size()) audio.resize(start + frames[i].audio.size(), 0.0f);
    for (std::size_t k = 0; k < frames[i].audio.size(); ++k) audio[start + k] += frames[i].audio[k];
  }
  return audio;
}

const std::vector<const Link*>& all_links() {
  static const std::vector<const Link*> links = [] {
    std::vector<const Link*> out;
    for (const LinkProfile* p : all_profiles()) {
      if (p->frame_format == FrameFormat::HoppedCommand)
        out.push_back(new FastLink(*p));
      else
        out.push_back(new SeedLink(*p));
    }
    return out;
  }();
  return links;
}

const Link& link_for(const LinkProfile& profile) {
  for (const Link* l : all_links()) {
    if (&l->profile() == &profile) return *l;
  }
  throw std::invalid_argument("no link for profile '" + profile.name + "'");
}

const Link& link_by_name(std::string_view name) { return link_for(profile_by_name(name)); }

}  // namespace dtmf::link
