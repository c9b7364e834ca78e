// clipping_test: to be written.
