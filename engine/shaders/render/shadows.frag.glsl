// Shadow casters write depth only.
void main() {}
