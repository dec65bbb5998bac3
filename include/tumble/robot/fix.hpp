#pragma once
// `tumble model fix`: a robot description with its inertials recomputed from its geometry and nothing
// else changed — every byte outside the rewritten <inertial> elements (MJCF: <inertial/>) as it was,
// each rewritten one marked with a comment that says it was computed by tumble and from what.
#include <string>
#include <vector>

#include "tumble/robot/audit.hpp"

namespace tumble::robot {

enum class Keep {
  mass,          ///< the authored mass, exactly as written; COM and tensor from the geometry
  mass_and_com,  ///< the authored mass and COM; the tensor from the geometry, about that COM
  none,          ///< everything from the geometry at a density (AuditOptions::density; MJCF: the geoms')
};

struct FixOptions {
  Keep keep = Keep::mass;
  std::vector<std::string> only;  ///< links to fix, whatever their findings; empty: those with findings
  bool all = false;               ///< every link with usable geometry, findings or not
};

/// What the fix did to one link.
struct LinkFix {
  std::string name;
  int line = 0;
  bool changed = false;
  std::string before, after;  ///< the element's text, before and after (when changed)
  std::string reason;         ///< why it was left as it was (when not changed)
};

struct FixResult {
  std::string text;  ///< the whole file, rewritten
  std::vector<LinkFix> links;
};

/// The model's text with the inertials of `audit`'s links recomputed: those with a finding the new
/// inertial answers (all of them with FixOptions::all; those named in FixOptions::only). A link without
/// an inertial gets none; one whose geometry could not be used, whose mesh is in other units, or whose
/// authored mass is 0 under Keep::mass, keeps its own (LinkFix::reason says why). Throws InvalidArgument for a name in `only` that is no link, and for
/// Keep::none without a density in a URDF or SDF file.
[[nodiscard]] FixResult fix_model(const ModelAudit& audit, const FixOptions& options,
                                  const AuditOptions& audit_options);

}  // namespace tumble::robot
