// empty.cpp — keeps the scene library non-empty while scenes are added.
