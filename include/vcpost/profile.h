// Machine profiles: what a machine's spindle, feed and control can do. The
// shipped ones (mazak-3axis, fanuc-3axis, linuxcnc-3axis, generic) are
// compiled in; your own are TOML files (schema: share/doc/vcpost, or
// machines/README.md in the sources).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vcpost/export.h"

namespace vcpost::machines {
class MachineProfile;
}

namespace vcpost::api {

class VCPOST_API MachineProfile {
 public:
  // The names of the shipped profiles, sorted.
  static std::vector<std::string> builtin_names();
  // A shipped profile's name or a TOML file, as `vcpost --machine` takes it.
  // Throws Error (E5009 unknown name, E5010 unreadable file, E5001-E5008
  // with file:line:col for a bad profile).
  static MachineProfile load(const std::string& name_or_file);
  // A profile from TOML text; `file_name` names it in messages.
  static MachineProfile from_toml(std::string_view text, const std::string& file_name);

  std::string name() const;
  std::string description() const;
  double spindle_min_rpm() const;
  double spindle_max_rpm() const;
  double spindle_acceleration_rpm_per_s() const;
  double spindle_deceleration_rpm_per_s() const;
  double feed_max_mm_per_min() const;
  // The complete profile as TOML, every key with its value and source note.
  std::string to_toml() const;

  // The library's own access to the validated profile.
  friend const machines::MachineProfile& internal(const MachineProfile& profile);

 private:
  explicit MachineProfile(std::shared_ptr<const machines::MachineProfile> profile);
  std::shared_ptr<const machines::MachineProfile> profile_;
};

}  // namespace vcpost::api
