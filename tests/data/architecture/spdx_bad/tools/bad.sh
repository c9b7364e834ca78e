#!/bin/sh
# A script without it.
exit 0
