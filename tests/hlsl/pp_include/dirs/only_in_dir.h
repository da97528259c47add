int fromDir;
