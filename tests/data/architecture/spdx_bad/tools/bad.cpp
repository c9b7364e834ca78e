// A source without the identifier: the check must name it.
int question() { return 6 * 9; }
