#include "strahl/version.h"

namespace strahl {

const char* version() { return STRAHL_VERSION_STRING; }

}  // namespace strahl
