// A planted back-include (layering_test.py must report it): control/ sits below daemon/ and may not include it.
#pragma once

#include "daemon/daemon.h"
