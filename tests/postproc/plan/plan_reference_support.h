// The whole-timeline reference of the spindle planner (see the .cpp).
#pragma once

#include <span>

#include "machines/profile.h"
#include "postproc/plan/spindle_plan.h"

namespace vcpost::plan::testing {

// The plan of spindle_plan.h over the whole timeline, pass by pass. Throws
// PlanError as plan_spindle().
SpindlePlan reference_plan_spindle(std::span<const Sample> samples,
                                   const machines::SpindleSpec& spec);

}  // namespace vcpost::plan::testing
