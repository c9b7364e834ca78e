// seed_mappings_test: to be written.
