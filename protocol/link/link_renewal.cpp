// Link::plan_renewal (link.h): the robots' links around the pure planner (renewal_planner.h).
// It gathers each robot's record, draws a fresh counter from each keyed candidate's store
// (the planner touches no store: one on disk is written here, by the link that owns it), and
// records what the plan used, so that no counter or renewal number ever serves twice.
#include <vector>

#include "link/link.h"

namespace dtmf::link {

namespace {

// The robots' links a joint renewal under `profile` may renew, as the planner sees them, and
// where each stands among the robots given.
struct Parties {
  std::vector<RenewalParty> parties;
  std::vector<std::size_t> robot_index;
};

Parties parties_of(std::span<Link* const> robots, const LinkProfile& profile) {
  Parties out;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    Link& l = *robots[i];
    const RenewalRecord* record = l.renewal_record();
    if (!record || &l.profile() != &profile) continue;
    out.parties.push_back({l.options().address, l.options().key.get(), *record, std::nullopt});
    out.robot_index.push_back(i);
  }
  return out;
}

}  // namespace

std::optional<Link::PlannedRenewal> Link::plan_renewal(std::span<Link* const> robots) {
  Parties p = parties_of(robots, profile());
  for (const std::size_t c : renewal_candidates(p.parties)) {
    if (p.parties[c].key) p.parties[c].fresh_counter = robots[p.robot_index[c]]->options().counters->next_counter();
  }
  const RenewalPlan plan = plan_joint_renewal(profile(), p.parties);
  for (const std::size_t n : plan.numbered) {
    Link& l = *robots[p.robot_index[n]];
    // Used here, whether or not its robot can take it.
    if (plan.counter) l.options().counters->next_counter_from(*plan.counter);
    if (plan.next_renewal_number) l.renewal_record()->next_renewal_number = *plan.next_renewal_number;
  }
  if (!plan.frame) return std::nullopt;
  PlannedRenewal planned{*plan.frame, {}};
  for (const std::size_t n : plan.renewed) planned.renewed.push_back(p.robot_index[n]);
  return planned;
}

}  // namespace dtmf::link
