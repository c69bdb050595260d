"""What suggest answers: one coefficient for the set, per colour, per group of roles, per icon."""

SCOPES = ("set", "colour", "group", "icon")
