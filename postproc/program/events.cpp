#include "postproc/program/events.h"

namespace vcpost::program {

SourceRef source_of(const Event& event) {
  return std::visit([](const auto& e) { return e.source; }, event);
}

bool is_motion(const Event& event) {
  return std::holds_alternative<StraightTraverse>(event) ||
         std::holds_alternative<StraightFeed>(event) || std::holds_alternative<ArcFeed>(event);
}

}  // namespace vcpost::program
