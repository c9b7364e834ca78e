// lens_curve_test: to be written.
