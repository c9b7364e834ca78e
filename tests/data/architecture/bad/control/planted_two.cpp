// ...and the other half here.
#include "control/planted.h"

namespace overlayd {

void Planted::second() {}

} // namespace overlayd
