#include "dtlab/common/build_info.hpp"

#include "dtlab_build_info.h"  // generated at every build (cmake/WriteBuildInfo.cmake)

namespace dtlab {

const char* version() {
  return DTLAB_VERSION;
}
const char* build_commit() {
  return DTLAB_COMMIT;
}

}  // namespace dtlab
