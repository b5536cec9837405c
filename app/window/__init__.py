"""The main window and the jobs around it: actions and menus, project files, background
tasks, the optimisation run, undo, autosave and recovery."""
