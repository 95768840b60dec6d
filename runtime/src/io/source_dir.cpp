#include "io/source_dir.h"

namespace lrigid {

std::string source_dir() {
#ifdef LRIGID_SOURCE_DIR
  return LRIGID_SOURCE_DIR;
#else
  return "";
#endif
}

}  // namespace lrigid
