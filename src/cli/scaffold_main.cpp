int main() { return 1; }  // replaced by the real program in the next commit
