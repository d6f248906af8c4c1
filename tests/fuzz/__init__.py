"""Property-based (hypothesis) tests of the command line and the file readers with random good and bad input."""
