int fixture() { return 0; }
