from linkgen.cli import main

main()
