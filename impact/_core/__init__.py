"""Generic numerical tools and process settings (no physics)."""
