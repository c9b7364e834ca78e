// scene_graph_test: to be written.
