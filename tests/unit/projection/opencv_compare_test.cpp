// opencv_compare_test: to be written.
