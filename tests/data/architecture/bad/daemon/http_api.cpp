// ...through its .cpp, a forward declaration in the header notwithstanding.
#include "daemon/http_api.h"

#include "daemon/daemon.h"
