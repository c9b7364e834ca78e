// unproject_test: to be written.
