// equivalence_test: to be written.
