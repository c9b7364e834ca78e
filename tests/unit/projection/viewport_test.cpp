// viewport_test: to be written.
