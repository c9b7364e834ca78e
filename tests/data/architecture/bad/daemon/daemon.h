// A planted cycle inside daemon/ (layering_test.py must report it): the header includes the API...
#pragma once

#include "daemon/http_api.h"
