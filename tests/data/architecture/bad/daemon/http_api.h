// ...and the API reaches back for the header that includes it.
#pragma once

class Daemon;
