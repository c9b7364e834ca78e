// A planted class spread over two files (layering_test.py must report it): half of Planted's members here...
#include "control/planted.h"

namespace overlayd {

void Planted::first() {}

} // namespace overlayd
