"""Developer tools (documentation generators); not imported by the compiler."""
