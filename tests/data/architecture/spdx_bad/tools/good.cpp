// SPDX-License-Identifier: Apache-2.0
// A source that carries the identifier.
int answer() { return 42; }
