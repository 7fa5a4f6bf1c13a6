"""Small reusable widgets and pictures."""
