// A fixture for the layering test: the blend wing reaching into a driver, which the layering forbids.
#pragma once

#include "drivers/v4l2/video_device.h"
