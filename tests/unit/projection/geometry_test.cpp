// geometry_test: to be written.
