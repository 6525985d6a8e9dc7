"""The quasi-static solution of a scene, its crush screen and the tolerance study on it."""
