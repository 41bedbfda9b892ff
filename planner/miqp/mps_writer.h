#pragma once
// Free-format MPS export of a Miqp, so any external MIQP solver can solve the identical
// problem. Integer columns sit between MARKER INTORG/INTEND lines; every column gets
// explicit bounds (readers disagree on defaults for integer columns); the quadratic
// objective is a QUADOBJ section (upper triangle, objective 0.5 x'Qx). The objective's
// constant is left out on purpose: readers disagree on the sign of an objective-row RHS,
// so it travels beside the file (plan JSON "objective_offset").
#include <ostream>
#include <string>

#include "planner/miqp/miqp.h"

namespace mfp {

void WriteMps(const Miqp& problem, const std::string& name, std::ostream& out);

// Throws InputError when the file cannot be written.
void WriteMpsFile(const Miqp& problem, const std::string& name, const std::string& path);

}  // namespace mfp
