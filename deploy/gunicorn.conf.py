"""Run SignStudy under gunicorn: ``gunicorn -c deploy/gunicorn.conf.py studyplatform.wsgi``.

`make demo` serves this way; a production site runs the same behind a TLS proxy
(docs/deployment.md). Threads serve the many short requests of participants' pages
(saves, events) while one waits on the database; the environment overrides each number.
"""

import multiprocessing
import os

bind = os.environ.get("SIGNSTUDY_BIND", "127.0.0.1:8000")
workers = int(os.environ.get("SIGNSTUDY_WORKERS", str(min(multiprocessing.cpu_count() * 2, 8))))
worker_class = "gthread"
threads = int(os.environ.get("SIGNSTUDY_THREADS", "8"))
# A signed answer's chunk or a results download may take a while on a slow connection.
timeout = int(os.environ.get("SIGNSTUDY_WORKER_TIMEOUT_S", "120"))
graceful_timeout = 30
keepalive = 5
# Restart a worker now and then, so a slow leak in a long study never grows unbounded.
max_requests = 5000
max_requests_jitter = 500
accesslog = os.environ.get("SIGNSTUDY_ACCESS_LOG") or None
# With the server's own time per request (ms), to tell queueing in front of it from work.
access_log_format = '%(h)s %(t)s "%(r)s" %(s)s %(b)s %(M)sms'

errorlog = "-"
loglevel = os.environ.get("SIGNSTUDY_LOG_LEVEL", "info").lower()
# Behind a proxy on this machine (nginx, Caddy): trust its X-Forwarded-* headers.
forwarded_allow_ips = os.environ.get("SIGNSTUDY_FORWARDED_ALLOW_IPS", "127.0.0.1,::1")
# gunicorn's control socket defaults to one path per user (~/.gunicorn/gunicorn.ctl), which
# every instance on the host shares: a second instance replaced the first's and stopping
# it deleted it. Off; SIGNSTUDY_CONTROL_SOCKET gives an instance a socket of its own.
_control_socket = os.environ.get("SIGNSTUDY_CONTROL_SOCKET", "")
control_socket_disable = not _control_socket
if _control_socket:
    control_socket = _control_socket
control_socket_mode = 0o600
