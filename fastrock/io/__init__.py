"""Records and files: the accelerogram readers, GroundMotion and the shipped record."""
