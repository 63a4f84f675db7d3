#include "gplanner/version.h"

namespace gplanner {

const char* version() { return GPLANNER_VERSION_STRING; }

}  // namespace gplanner
