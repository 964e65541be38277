// Included by the test shaders, so the build and the tests exercise #include.
float affine(float x, float scale, float offset) { return x * scale + offset; }
