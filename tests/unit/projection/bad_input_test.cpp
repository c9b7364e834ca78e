// bad_input_test: to be written.
