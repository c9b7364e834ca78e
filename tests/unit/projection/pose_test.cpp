// pose_test: to be written.
