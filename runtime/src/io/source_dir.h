// The source tree this program was built from: where lrigid finds its own files (the tolerance
// table, the default bench scene) when they are not next to the binary. Defined in a file of its
// own, so that the path is compiled into one small unit and the others do not depend on it.
#pragma once
#include <string>

namespace lrigid {

// the source tree's absolute path, or "" when the build did not record one
std::string source_dir();

}  // namespace lrigid
