// glm_matrices_test: to be written.
