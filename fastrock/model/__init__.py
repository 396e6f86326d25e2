"""Model descriptions: bodies, excitations, walls, friction and foundations (values only;
nothing here runs a kernel)."""
