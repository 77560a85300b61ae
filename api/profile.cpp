#include "vcpost/profile.h"

#include "api/translate.h"
#include "machines/builtin.h"
#include "machines/profile.h"
#include "postproc/cli/commands.h"

namespace vcpost::api {

MachineProfile::MachineProfile(std::shared_ptr<const machines::MachineProfile> profile)
    : profile_(std::move(profile)) {}

std::vector<std::string> MachineProfile::builtin_names() {
  std::vector<std::string> names;
  for (const auto& entry : machines::builtin_profiles()) names.emplace_back(entry.name);
  return names;
}

MachineProfile MachineProfile::load(const std::string& name_or_file) {
  return guarded([&] {
    return MachineProfile(
        std::make_shared<const machines::MachineProfile>(cli::load_machine(name_or_file)));
  });
}

MachineProfile MachineProfile::from_toml(std::string_view text, const std::string& file_name) {
  return guarded([&] {
    return MachineProfile(std::make_shared<const machines::MachineProfile>(
        machines::profile_from_toml(text, file_name)));
  });
}

std::string MachineProfile::name() const { return profile_->name(); }
std::string MachineProfile::description() const { return profile_->description(); }
double MachineProfile::spindle_min_rpm() const { return profile_->spindle().n_min_rpm; }
double MachineProfile::spindle_max_rpm() const { return profile_->spindle().n_max_rpm; }
double MachineProfile::spindle_acceleration_rpm_per_s() const {
  return profile_->spindle().acceleration_rpm_per_s;
}
double MachineProfile::spindle_deceleration_rpm_per_s() const {
  return profile_->spindle().deceleration_rpm_per_s;
}
double MachineProfile::feed_max_mm_per_min() const { return profile_->feed().f_max_mm_per_min; }
std::string MachineProfile::to_toml() const { return machines::profile_to_toml(*profile_); }

const machines::MachineProfile& internal(const MachineProfile& profile) {
  return *profile.profile_;
}

}  // namespace vcpost::api
